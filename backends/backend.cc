#include "backends/backend.h"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <stdexcept>

#include "backends/cpu_backend.h"
#include "backends/robocore_backend.h"
#include "backends/simt_backend.h"
#include "backends/ttaplus_backend.h"
#include "common/loop_exceptions.h"
#include "robocore/ray_batch_recorded.h"

namespace rc {

std::unique_ptr<Backend> Backend::Create(const std::string& name, const BackendParameters& params) {
  std::string error;
  if (!params.IsValid(&error)) throw std::invalid_argument("backend parameters: " + error);
  if (name == "cpu") return std::make_unique<CpuBackend>();
  if (name == "simt") return std::make_unique<SimtBackend>(params);
  if (name == "ttaplus") return std::make_unique<TtaPlusBackend>(params, EarlyExitMode::kNone);
  if (name == "ttaplus-p") return std::make_unique<TtaPlusBackend>(params, EarlyExitMode::kPredication);
  if (name == "ttaplus-cr") return std::make_unique<TtaPlusBackend>(params, EarlyExitMode::kConditionalReturn);
  if (name == "robocore") return std::make_unique<RoboCoreBackend>(params);
  throw std::invalid_argument("unknown backend '" + name +
                              "' (expected cpu, simt, ttaplus, ttaplus-p, ttaplus-cr or robocore)");
}

std::vector<std::string> Backend::Names() { return {"cpu", "simt", "ttaplus", "ttaplus-p", "ttaplus-cr", "robocore"}; }

std::vector<std::string> Backend::ModelledNames() { return {"simt", "ttaplus", "ttaplus-p", "ttaplus-cr", "robocore"}; }

BatchCost Backend::Price(const KernelRecord& record) const {
  PricingContext context(record);
  return Price(record, context);
}

BatchCost Backend::Price(const KernelRecord& record, PricingContext& context) const {
  if (&context.record() != &record)
    throw std::invalid_argument("Backend::Price: the pricing context belongs to another record");
  return DoPrice(record, context);
}

BatchCost Backend::Run(const RayCastScene& scene, const RayBatch& batch, std::vector<RayHit>& hits) const {
  const auto start = std::chrono::steady_clock::now();
  KernelRecord record;
  CastRayBatchRecorded(scene, batch, hits, record);
  const double host = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  BatchCost cost = Price(record);
  cost.host_seconds = host;
  return cost;
}

template <typename Scalar>
BatchCost Backend::RunCollisions(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                                 std::vector<CollisionResult>& results, const CollisionOptions<Scalar>& options) const {
  const auto start = std::chrono::steady_clock::now();
  KernelRecord record;
  RoboCoreContext().CheckCollisions(obbs, tree, results, record, options);
  const double host = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  BatchCost cost = Price(record);
  cost.host_seconds = host;
  return cost;
}
template BatchCost Backend::RunCollisions(const FlatBoxTree<float>&, const std::vector<Obb<float>>&,
                                          std::vector<CollisionResult>&, const CollisionOptions<float>&) const;
template BatchCost Backend::RunCollisions(const FlatBoxTree<double>&, const std::vector<Obb<double>>&,
                                          std::vector<CollisionResult>&, const CollisionOptions<double>&) const;

BatchCost& BatchCost::operator+=(const BatchCost& more) {
  // SIMT efficiency is active lanes over issued lanes, so the sum is the
  // issued-instruction-weighted mean.
  const double wa = static_cast<double>(warp_instructions), wb = static_cast<double>(more.warp_instructions);
  if (wa + wb > 0) simt_efficiency = (simt_efficiency * wa + more.simt_efficiency * wb) / (wa + wb);
  host_seconds += more.host_seconds;
  queries += more.queries;
  nodes += more.nodes;
  cycles += more.cycles;
  launch_cycles += more.launch_cycles;
  seconds += more.seconds;
  energy_joules += more.energy_joules;
  memory += more.memory;
  for (std::size_t k = 0; k < micro_ops.size(); ++k) micro_ops[k] += more.micro_ops[k];
  predicated_off_micro_ops += more.predicated_off_micro_ops;
  interconnect_hops += more.interconnect_hops;
  ctrl_exits += more.ctrl_exits;
  warp_instructions += more.warp_instructions;
  thread_instructions += more.thread_instructions;
  nodes_counted += more.nodes_counted;
  return *this;
}

BatchCost BatchCost::ScaledBy(double factor) const {
  auto scaled = [factor](std::uint64_t count) {
    return static_cast<std::uint64_t>(std::llround(static_cast<double>(count) * factor));
  };
  BatchCost out = *this;
  out.host_seconds *= factor;
  out.seconds *= factor;
  out.energy_joules *= factor;
  for (std::uint64_t* count :
       {&out.queries, &out.nodes, &out.cycles, &out.launch_cycles, &out.memory.sector_requests, &out.memory.l1_hits,
        &out.memory.l2_accesses, &out.memory.l2_hits, &out.memory.dram_accesses, &out.predicated_off_micro_ops,
        &out.interconnect_hops, &out.ctrl_exits, &out.warp_instructions, &out.thread_instructions, &out.nodes_counted})
    *count = scaled(*count);
  for (std::uint64_t& ops : out.micro_ops) ops = scaled(ops);
  return out;
}

std::vector<BatchCost> PriceAll(const std::vector<const Backend*>& backends, const KernelRecord& record) {
  // The work the backends share is computed first, spread over the threads
  // (PricingContext::ComputeExpected); then the backends price in parallel.
  // Each backend's price does not depend on the order.
  PricingContext context(record);
  for (const Backend* b : backends) b->AnnouncePricing(record, context);
  context.ComputeExpected();
  std::vector<BatchCost> costs(backends.size());
  LoopExceptions exceptions(backends.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (long i = 0; i < static_cast<long>(backends.size()); ++i)
    exceptions.Run(static_cast<std::size_t>(i), [&] { costs[i] = backends[i]->Price(record, context); });
  exceptions.RethrowFirst();
  return costs;
}

void PrintBatchCost(std::ostream& out, const BatchCost& c) {
  out << c.backend << ": " << c.queries << " queries, " << c.nodes << " nodes";
  if (!c.modelled) {
    out << ", host " << c.host_seconds << " s (no cost model)\n";
    return;
  }
  out << "\n  cycles " << c.cycles << " (launch " << c.launch_cycles << ") = " << c.seconds << " s at "
      << c.clock_hz / 1e6 << " MHz, bound: " << c.bound << "\n  energy " << c.energy_joules << " J";
  if (c.simt_efficiency == c.simt_efficiency) out << ", SIMT efficiency " << c.simt_efficiency;
  out << "\n  sectors " << c.memory.sector_requests << ", L1 hits " << c.memory.l1_hits << ", L2 "
      << c.memory.l2_accesses << " (hits " << c.memory.l2_hits << "), DRAM " << c.memory.dram_accesses
      << "\n  L1 model " << c.l1_model << "; L2 model " << c.l2_model << "\n  micro-ops:";
  for (int i = 0; i < kOpcodeCount; ++i)
    if (c.micro_ops[i]) out << ' ' << MnemonicOf(static_cast<Opcode>(i)) << '=' << c.micro_ops[i];
  out << "\n  hops " << c.interconnect_hops << ", predicated off " << c.predicated_off_micro_ops << ", CTRL exits "
      << c.ctrl_exits << ", nodes counted " << c.nodes_counted;
  if (c.warp_instructions)
    out << ", warp instructions " << c.warp_instructions << ", thread instructions " << c.thread_instructions;
  out << "\n";
}

}  // namespace rc
