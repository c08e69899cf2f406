#include "backends/simt_backend.h"

#include <algorithm>
#include <stdexcept>

#include "backends/energy_model.h"
#include "backends/modelled_backend.h"
#include "backends/warp_nodes.h"
#include "backends/warp_schedule.h"
#include "robocore/shipped_programs.h"

namespace rc {
namespace {

enum Pipe : int { kFp32Pipe, kIntPipe, kSfuPipe, kFp64Pipe, kLdStPipe, kPipeCount };
constexpr const char* kPipeBound[kPipeCount] = {"FP32 pipe", "INT pipe", "SFU pipe", "FP64 pipe", "LD/ST pipe"};

struct ClassTiming {
  std::uint64_t latency;     // core cycles added to the warp's dependent chain
  std::uint64_t initiation;  // core cycles the class holds its pipe
  Pipe pipe;
};

std::array<ClassTiming, kSimtClassCount> Timings(const SimtParams& s) {
  auto u = [](int v) { return static_cast<std::uint64_t>(v); };
  const Pipe fp64_pipe = s.fp64_units_per_scheduler > 0 ? kFp64Pipe : kSfuPipe;
  std::array<ClassTiming, kSimtClassCount> t{};
  t[static_cast<int>(SimtClass::kFp32)] = {u(s.fp32_latency_cycles), u(s.fp32_initiation_cycles), kFp32Pipe};
  t[static_cast<int>(SimtClass::kFp64)] = {u(s.fp64_latency_cycles), u(s.fp64_initiation_cycles), fp64_pipe};
  t[static_cast<int>(SimtClass::kInt)] = {u(s.int_latency_cycles), u(s.int_initiation_cycles), kIntPipe};
  t[static_cast<int>(SimtClass::kFp32Div)] = {u(s.fp32_div_latency_cycles), u(s.fp32_div_initiation_cycles), kSfuPipe};
  t[static_cast<int>(SimtClass::kFp64Div)] = {u(s.fp64_div_latency_cycles), u(s.fp64_div_initiation_cycles), kSfuPipe};
  t[static_cast<int>(SimtClass::kIntDiv)] = {u(s.int_div_latency_cycles), u(s.int_div_initiation_cycles), kSfuPipe};
  t[static_cast<int>(SimtClass::kSfu)] = {u(s.sfu_latency_cycles), u(s.sfu_initiation_cycles), kSfuPipe};
  t[static_cast<int>(SimtClass::kLoad)] = {0, 1, kLdStPipe};
  t[static_cast<int>(SimtClass::kStore)] = {0, 1, kLdStPipe};
  t[static_cast<int>(SimtClass::kBranch)] = {u(s.other_latency_cycles), u(s.other_initiation_cycles), kFp32Pipe};
  t[static_cast<int>(SimtClass::kOther)] = {u(s.other_latency_cycles), u(s.other_initiation_cycles), kFp32Pipe};
  return t;
}

// The fallback's class of one micro-op's scalar instructions.
SimtClass FallbackClass(Opcode op, bool fp64) {
  switch (op) {
    case Opcode::kCmp:
    case Opcode::kAnd:
    case Opcode::kOr:
    case Opcode::kXor:
    case Opcode::kNot: return SimtClass::kOther;
    case Opcode::kPush: return SimtClass::kInt;
    case Opcode::kRcp: return SimtClass::kSfu;
    case Opcode::kReturn:
    case Opcode::kReturnIf: return SimtClass::kBranch;
    default: return fp64 ? SimtClass::kFp64 : SimtClass::kFp32;
  }
}

const CompiledSections& SectionsOf(const CompiledKernel& k, SimtIsa isa) {
  if (isa == SimtIsa::kSass && !k.has_sass)
    throw std::invalid_argument("simt.isa = sass: the instruction table has no SASS for " + k.name);
  return isa == SimtIsa::kSass ? k.sass : k.ptx;
}

// What one thread's execution of a section does, as written in the program
// (micro-op counts and arithmetic energy; instructions come from the mix).
struct SectionWork {
  std::array<std::uint64_t, kOpcodeCount> micro_ops{};
  double arithmetic_joules = 0;
};

}  // namespace

SimtBackend::SimtBackend(const BackendParameters& params)
    : gpu_(params.gpu), simt_(params.simt), energy_(params.energy) {
  specs_ = ModelledBackendSpecs("simt", "CUDA cores: warps of 32 queries, coalesced sectors, GTO issue", gpu_);
  if (simt_.isa == SimtIsa::kSass && !SimtInstructionTable::Shipped().has_sass())
    throw std::invalid_argument("simt.isa = sass, but the instruction table holds no SASS counts");
}

SimtClassCounts SimtBackend::FallbackInstructions(const std::vector<MicroOp>& ops, bool loop, bool fp64) const {
  SimtClassCounts n{};
  if (loop) n[static_cast<int>(SimtClass::kBranch)] += static_cast<std::uint64_t>(simt_.loop_branch_instructions);
  auto add = [&](Opcode op, int width) {
    n[static_cast<int>(FallbackClass(op, fp64))] +=
        static_cast<std::uint64_t>(simt_.instructions_per_element[static_cast<int>(op)] * width);
  };
  for (const MicroOp& op : ops) {
    if (op.opcode == Opcode::kLoad) {
      n[static_cast<int>(SimtClass::kLoad)] += 1;
      n[static_cast<int>(SimtClass::kInt)] += static_cast<std::uint64_t>(simt_.instructions_per_load - 1);
    } else if (InfoOf(op.opcode).sact) {
      for (const ExpandedOp& e : TtaPlusExpansion(op.opcode)) add(e.opcode, e.width);
    } else {
      add(op.opcode, op.width);
    }
  }
  return n;
}

SimtInstructionMix SimtBackend::InstructionMix(const KernelRecord& record) const {
  SimtInstructionMix mix;
  mix.fp64 =
      simt_.precision == SimtPrecision::kHost ? record.scalar_bytes != 4 : simt_.precision == SimtPrecision::kFp64;
  const char* precision = mix.fp64 ? "fp64" : "fp32";
  // The RT units' cost description may be a shipped variant (the artifact's
  // march); the CUDA cores run the same kernel, compiled.
  const bool shipped_program = IsShippedProgramOf(record.step_kind, record.program);
  const bool beam_leaf = record.leaf_kind == LeafProgramKind::kBeamModel && record.leaf &&
                         record.leaf == ShippedLeafProgram(LeafProgramKind::kBeamModel);
  const SimtInstructionTable& table = SimtInstructionTable::Shipped();
  const CompiledKernel* kernel = shipped_program ? table.Find(ShippedProgramFile(record.step_kind), mix.fp64,
                                                              beam_leaf ? simt_.beam_leaf : SimtBeamLeaf::kNone)
                                                 : nullptr;
  const bool leaf_compiled = kernel && (beam_leaf || !record.leaf);
  if (!kernel && shipped_program && beam_leaf)  // a program compiled without the leaf: the leaf falls back
    kernel = table.Find(ShippedProgramFile(record.step_kind), mix.fp64, SimtBeamLeaf::kNone);

  if (kernel) {
    const CompiledSections& s = SectionsOf(*kernel, simt_.isa);
    mix.once = s.prologue;
    mix.once += s.epilogue;
    mix.pass = s.loop;
    mix.registers = kernel->registers;
    mix.compiled = true;
    mix.source = std::string("compiled ") + kernel->name + " (" + (simt_.isa == SimtIsa::kSass ? "SASS" : "PTX") +
                 ", " + table.nvcc().substr(table.nvcc().rfind(' ') + 1) + ", " + table.arch() + ")";
  } else {
    const MicroProgram& program = *record.program;
    mix.once = FallbackInstructions(program.section(ProgramSection::kPrologue), false, mix.fp64);
    mix.once += FallbackInstructions(program.section(ProgramSection::kEpilogue), false, mix.fp64);
    mix.pass = FallbackInstructions(program.section(ProgramSection::kLoop), true, mix.fp64);
    mix.registers = simt_.fallback_registers_per_thread;
    mix.source =
        std::string("per-op fallback (") + precision + "): program '" + program.name() + "' has no compiled kernel";
  }
  if (record.leaf && !leaf_compiled) {
    mix.once += FallbackInstructions(record.leaf->section(ProgramSection::kEpilogue), false, mix.fp64);
    if (kernel) mix.source += "; leaf '" + record.leaf->name() + "' by the per-op fallback";
  }
  if (simt_.registers_per_thread > 0) mix.registers = simt_.registers_per_thread;
  return mix;
}

AccessPattern SimtBackend::MemoryPattern(const SimtInstructionMix& mix) const {
  return AccessPattern{simt_.ResidentWarps(gpu_, mix.registers), true};
}

void SimtBackend::AnnouncePricing(const KernelRecord& record, PricingContext& context) const {
  context.ExpectMemory(gpu_, MemoryPattern(InstructionMix(record)));
}

BatchCost SimtBackend::DoPrice(const KernelRecord& record, PricingContext& context) const {
  const SimtInstructionMix mix = InstructionMix(record);
  const AccessPattern pattern = MemoryPattern(mix);
  const int resident = pattern.warps_per_wave;
  const auto memory = context.Memory(gpu_, pattern);
  const auto timing = Timings(simt_);

  auto work_of = [&](const std::vector<MicroOp>& ops) {
    SectionWork w;
    for (const MicroOp& op : ops) {
      ++w.micro_ops[static_cast<int>(op.opcode)];
      w.arithmetic_joules += ArithmeticEnergyJoules(ContentOf(op.opcode, op.width), energy_);
    }
    return w;
  };
  const MicroProgram& program = *record.program;
  SectionWork once = work_of(program.section(ProgramSection::kPrologue));
  for (const std::vector<MicroOp>* ops : {&program.section(ProgramSection::kEpilogue),
                                          record.leaf ? &record.leaf->section(ProgramSection::kEpilogue) : nullptr}) {
    if (!ops) continue;
    const SectionWork w = work_of(*ops);
    for (int i = 0; i < kOpcodeCount; ++i) once.micro_ops[i] += w.micro_ops[i];
    once.arithmetic_joules += w.arithmetic_joules;
  }
  const SectionWork pass = work_of(program.section(ProgramSection::kLoop));

  const std::uint64_t once_total = Total(mix.once), pass_total = Total(mix.pass);
  std::uint64_t once_latency = 0, pass_latency = 0;
  for (int c = 0; c < kSimtClassCount; ++c) {
    once_latency += mix.once[c] * timing[c].latency;
    pass_latency += mix.pass[c] * timing[c].latency;
  }

  const std::size_t n = record.query_count();
  const std::size_t warps = WarpCount(record, gpu_);
  std::vector<std::vector<std::uint64_t>> sm_latencies(gpu_.sms);
  std::vector<SimtClassCounts> sm_classes(gpu_.sms, SimtClassCounts{});
  std::uint64_t warp_instructions = 0, thread_instructions = 0;
  const auto warp_nodes = context.WarpNodes(gpu_.warp_size);
  const std::vector<std::uint32_t>& warp_steps = warp_nodes->steps;
  const std::vector<std::uint64_t>& warp_lane_nodes = warp_nodes->lane_nodes;
  // Warp w's SM (SmOfWarp) followed block by block rather than divided out
  // warp by warp.
  int sm = 0, warp_in_block = 0;
  for (std::size_t w = 0; w < warps; ++w) {
    const std::size_t lo = w * gpu_.warp_size, hi = std::min(n, lo + gpu_.warp_size);
    const std::uint64_t steps = warp_steps[w];
    const std::uint64_t lane_nodes = warp_lane_nodes[w];
    warp_instructions += once_total + steps * pass_total;
    thread_instructions += (hi - lo) * once_total + lane_nodes * pass_total;
    for (int c = 0; c < kSimtClassCount; ++c) sm_classes[sm][c] += mix.once[c] + steps * mix.pass[c];
    sm_latencies[sm].push_back(once_latency + steps * pass_latency + memory->warp_memory_cycles[w]);
    if (++warp_in_block == gpu_.warps_per_block) {
      warp_in_block = 0;
      if (++sm == gpu_.sms) sm = 0;
    }
  }

  BatchCost cost = ModelledBatchCost(specs_.name, record, gpu_, *memory);
  std::uint64_t busiest = 0;
  const std::uint64_t schedulers = static_cast<std::uint64_t>(simt_.schedulers_per_sm);
  const std::uint64_t issue_rate = schedulers * static_cast<std::uint64_t>(simt_.issue_per_scheduler_per_cycle);
  const std::uint64_t fp64_units = static_cast<std::uint64_t>(std::max(1, simt_.fp64_units_per_scheduler));
  for (int sm = 0; sm < gpu_.sms; ++sm) {
    std::uint64_t cycles = Makespan(sm_latencies[sm], resident);
    std::string bound = "latency (resident warps)";
    auto consider = [&](std::uint64_t c, const char* what) {
      if (c > cycles) {
        cycles = c;
        bound = what;
      }
    };
    // Every instruction takes an issue slot; each scheduler's pipe takes a
    // new warp instruction of a class every initiation interval of it.
    consider(CeilDiv(Total(sm_classes[sm]), issue_rate), "issue");
    std::array<std::uint64_t, kPipeCount> busy{};
    for (int c = 0; c < kSimtClassCount; ++c) busy[timing[c].pipe] += sm_classes[sm][c] * timing[c].initiation;
    for (int p = 0; p < kPipeCount; ++p)
      consider(CeilDiv(busy[p], schedulers * (p == kFp64Pipe ? fp64_units : 1)), kPipeBound[p]);
    consider(CeilDiv(memory->sm_sector_requests[sm], static_cast<std::uint64_t>(simt_.l1_sectors_per_cycle)),
             "L1 bandwidth");
    if (cycles >= busiest) {
      busiest = cycles;
      cost.bound = bound;
    }
  }
  FinishKernelCycles(cost, static_cast<std::uint64_t>(gpu_.kernel_launch_cycles), busiest, gpu_);
  cost.warp_instructions = warp_instructions;
  cost.thread_instructions = thread_instructions;
  cost.simt_efficiency = warp_instructions == 0
                             ? 1.0
                             : static_cast<double>(thread_instructions) /
                                   (static_cast<double>(gpu_.warp_size) * static_cast<double>(warp_instructions));
  for (int i = 0; i < kOpcodeCount; ++i) cost.micro_ops[i] = n * once.micro_ops[i] + cost.nodes * pass.micro_ops[i];
  cost.nodes_counted = cost.micro_ops[static_cast<int>(Opcode::kPush)];
  cost.energy_joules =
      static_cast<double>(n) * once.arithmetic_joules + static_cast<double>(cost.nodes) * pass.arithmetic_joules +
      Sram32kbJoules(static_cast<double>(warp_instructions) * energy_.simt_icache_accesses_per_warp_instruction,
                     energy_) +
      Sram8kbJoules(static_cast<double>(thread_instructions) * energy_.simt_register_accesses_per_thread_instruction,
                    energy_) +
      MemoryEnergyJoules(memory->totals, gpu_, energy_);
  return cost;
}

}  // namespace rc
