#include "backends/simt_backend.h"

#include <algorithm>
#include <stdexcept>

#include "backends/energy_model.h"
#include "backends/modelled_backend.h"
#include "backends/warp_schedule.h"

namespace rc {
namespace {

// What one thread's execution of a section does, as written in the program.
struct SectionWork {
  std::uint64_t instructions = 0;
  std::array<std::uint64_t, kOpcodeCount> micro_ops{};
  double arithmetic_joules = 0;
};

}  // namespace

SimtBackend::SimtBackend(const BackendParameters& params)
    : gpu_(params.gpu), simt_(params.simt), energy_(params.energy) {
  specs_ = ModelledBackendSpecs("simt", "CUDA cores: warps of 32 queries, coalesced sectors, GTO issue", gpu_);
}

std::uint64_t SimtBackend::SectionInstructions(const std::vector<MicroOp>& ops, bool loop) const {
  std::uint64_t n = loop ? static_cast<std::uint64_t>(simt_.loop_branch_instructions) : 0;
  for (const MicroOp& op : ops) {
    if (op.opcode == Opcode::kLoad) {
      n += static_cast<std::uint64_t>(simt_.instructions_per_load);
    } else if (InfoOf(op.opcode).sact) {
      for (const ExpandedOp& e : TtaPlusExpansion(op.opcode))
        n += static_cast<std::uint64_t>(simt_.instructions_per_element[static_cast<int>(e.opcode)] * e.width);
    } else {
      n += static_cast<std::uint64_t>(simt_.instructions_per_element[static_cast<int>(op.opcode)] * op.width);
    }
  }
  return n;
}

BatchCost SimtBackend::DoPrice(const KernelRecord& record, PricingContext& context) const {
  const int resident = simt_.ResidentWarps(gpu_);
  const auto memory = context.Memory(gpu_, AccessPattern{resident, true});

  auto work_of = [&](const std::vector<MicroOp>& ops, bool loop) {
    SectionWork w;
    w.instructions = SectionInstructions(ops, loop);
    for (const MicroOp& op : ops) {
      ++w.micro_ops[static_cast<int>(op.opcode)];
      w.arithmetic_joules += ArithmeticEnergyJoules(ContentOf(op.opcode, op.width), energy_);
    }
    return w;
  };
  const MicroProgram& program = *record.program;
  SectionWork once = work_of(program.section(ProgramSection::kPrologue), false);
  for (const std::vector<MicroOp>* ops :
       {&program.section(ProgramSection::kEpilogue),
        record.leaf ? &record.leaf->section(ProgramSection::kEpilogue) : nullptr}) {
    if (!ops) continue;
    const SectionWork w = work_of(*ops, false);
    once.instructions += w.instructions;
    for (int i = 0; i < kOpcodeCount; ++i) once.micro_ops[i] += w.micro_ops[i];
    once.arithmetic_joules += w.arithmetic_joules;
  }
  const SectionWork pass = work_of(program.section(ProgramSection::kLoop), true);

  const std::size_t n = record.query_count();
  const std::size_t warps = WarpCount(record, gpu_);
  std::vector<std::vector<std::uint64_t>> sm_latencies(gpu_.sms);
  std::vector<std::uint64_t> sm_instructions(gpu_.sms, 0);
  std::uint64_t warp_instructions = 0, thread_instructions = 0;
  for (std::size_t w = 0; w < warps; ++w) {
    const std::size_t lo = w * gpu_.warp_size, hi = std::min(n, lo + gpu_.warp_size);
    std::uint64_t steps = 0;
    for (std::size_t q = lo; q < hi; ++q) steps = std::max<std::uint64_t>(steps, record.nodes(q));
    const std::uint64_t lane_nodes = record.fetch_offsets[hi] - record.fetch_offsets[lo];
    const std::uint64_t issued = once.instructions + steps * pass.instructions;
    warp_instructions += issued;
    thread_instructions += (hi - lo) * once.instructions + lane_nodes * pass.instructions;
    const int sm = SmOfWarp(w, gpu_);
    sm_instructions[sm] += issued;
    sm_latencies[sm].push_back(issued * static_cast<std::uint64_t>(simt_.dependent_instruction_latency_cycles) +
                               memory->warp_memory_cycles[w]);
  }

  BatchCost cost = ModelledBatchCost(specs_.name, record, gpu_, *memory);
  std::uint64_t busiest = 0;
  const std::uint64_t issue_rate =
      static_cast<std::uint64_t>(simt_.schedulers_per_sm) * simt_.issue_per_scheduler_per_cycle;
  for (int sm = 0; sm < gpu_.sms; ++sm) {
    std::uint64_t cycles = Makespan(sm_latencies[sm], resident);
    std::string bound = "latency (resident warps)";
    auto consider = [&](std::uint64_t c, const char* what) {
      if (c > cycles) {
        cycles = c;
        bound = what;
      }
    };
    // Every instruction takes an issue slot; the ALU of each scheduler takes
    // a new warp instruction every alu_initiation_cycles. Loads and branches
    // use other units, but they are a minority of these loop bodies, so all
    // instructions are charged to the ALU (slightly pessimistic).
    consider(std::max(CeilDiv(sm_instructions[sm], issue_rate),
                      CeilDiv(sm_instructions[sm] * static_cast<std::uint64_t>(simt_.alu_initiation_cycles),
                              static_cast<std::uint64_t>(simt_.schedulers_per_sm))),
             "issue");
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
  cost.simt_efficiency =
      warp_instructions == 0 ? 1.0
                             : static_cast<double>(thread_instructions) /
                                   (static_cast<double>(gpu_.warp_size) * static_cast<double>(warp_instructions));
  for (int i = 0; i < kOpcodeCount; ++i)
    cost.micro_ops[i] = n * once.micro_ops[i] + cost.nodes * pass.micro_ops[i];
  cost.nodes_counted = cost.micro_ops[static_cast<int>(Opcode::kPush)];
  cost.energy_joules =
      static_cast<double>(n) * once.arithmetic_joules + static_cast<double>(cost.nodes) * pass.arithmetic_joules +
      Sram32kbJoules(static_cast<double>(warp_instructions) * energy_.simt_icache_accesses_per_warp_instruction,
                     energy_) +
      Sram8kbJoules(static_cast<double>(thread_instructions) *
                        energy_.simt_register_accesses_per_thread_instruction,
                    energy_) +
      MemoryEnergyJoules(memory->totals, gpu_, energy_);
  return cost;
}

}  // namespace rc
