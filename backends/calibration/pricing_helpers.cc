#include "backends/calibration/pricing_helpers.h"

#include <memory>

#include "robocore/section_timing.h"

namespace rc {

std::map<std::string, BatchCost> PriceByName(const std::vector<std::string>& names, const KernelRecord& record,
                                             const BackendParameters& params) {
  std::vector<std::unique_ptr<Backend>> owned;
  std::vector<const Backend*> backends;
  for (const std::string& name : names) {
    owned.push_back(Backend::Create(name, params));
    backends.push_back(owned.back().get());
  }
  const std::vector<BatchCost> costs = PriceAll(backends, record);
  std::map<std::string, BatchCost> by_name;
  for (std::size_t i = 0; i < names.size(); ++i) by_name[names[i]] = costs[i];
  return by_name;
}

double KernelSeconds(const BatchCost& cost) {
  return static_cast<double>(cost.cycles - cost.launch_cycles) / cost.clock_hz;
}

std::uint64_t MicroOpsExecuted(const BatchCost& cost) {
  std::uint64_t n = 0;
  for (int i = 0; i < kOpcodeCount; ++i)
    if (static_cast<Opcode>(i) != Opcode::kLoad) n += cost.micro_ops[i];
  return n;
}

double AverageComputationCycles(const KernelRecord& record, const DatapathConfig& datapath) {
  const ProgramTiming timing(*record.program, record.leaf.get(), datapath);
  double cycles = static_cast<double>(timing.once().cycles) * static_cast<double>(record.query_count());
  for (std::size_t q = 0; q < record.query_count(); ++q)
    for (std::uint32_t k = 0; k < record.nodes(q); ++k) cycles += timing.loop.Cost(record.ExitAt(q, k)).cycles;
  return cycles / static_cast<double>(record.query_count());
}

LoopMix LoopMixOf(const MicroProgram& program) {
  LoopMix mix;
  for (const MicroOp& op : program.section(ProgramSection::kLoop)) {
    if (op.opcode == Opcode::kLoad || op.opcode == Opcode::kReturnIf) continue;
    ++mix.micro_ops;
    mix.compares += op.opcode == Opcode::kCmp;
  }
  return mix;
}

}  // namespace rc
