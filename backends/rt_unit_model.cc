#include "backends/rt_unit_model.h"

#include <algorithm>
#include <array>

#include "backends/energy_model.h"
#include "backends/modelled_backend.h"
#include "backends/ray_query_cycles.h"
#include "backends/rt_warp_cycles.h"
#include "backends/warp_schedule.h"

namespace rc {
namespace {

// Everything a set of executions of one section cost, scaled by a count.
struct Tally {
  std::array<std::uint64_t, kOpcodeCount> executed{};
  std::array<std::uint64_t, kOpUnitCount> unit_slots{};
  std::uint64_t hops = 0, predicated = 0, ctrl = 0, pushes = 0, micro_ops = 0;
  double arithmetic_joules = 0;

  void Add(const SectionCost& c, std::uint64_t times, const EnergyParams& e) {
    if (times == 0) return;
    for (int i = 0; i < kOpcodeCount; ++i) {
      executed[i] += times * c.executed[i];
      if (static_cast<Opcode>(i) != Opcode::kLoad) micro_ops += times * c.executed[i];
    }
    for (int i = 0; i < kOpUnitCount; ++i) unit_slots[i] += times * c.unit_slots[i];
    hops += times * c.hops;
    predicated += times * c.predicated_off;
    ctrl += times * c.ctrl_exits;
    pushes += times * c.pushes;
    arithmetic_joules += static_cast<double>(times) * ArithmeticEnergyJoules(c.arithmetic, e);
  }
};

// A query's costs on this timing (ray_query_cycles.h, rt_warp_cycles.h): the
// loop's variants are 0 = no exit, 1 + j = RETURN_IF j.
RayPassCosts PassCostsOf(const ProgramTiming& timing) {
  RayPassCosts costs;
  costs.once_cycles = timing.once().cycles;
  costs.quiet_pass_cycles = timing.loop.Cost(kNoExit).cycles;
  costs.last_pass_cycles.fill(costs.quiet_pass_cycles);
  for (int j = 0; j < timing.loop.return_count(); ++j)
    costs.last_pass_cycles[j] = timing.loop.Cost(static_cast<std::uint8_t>(j)).cycles;
  return costs;
}

}  // namespace

void AnnounceRtUnit(const KernelRecord& record, PricingContext& context, const RtUnitPricing& pricing) {
  const AccessPattern pattern = RtUnitAccessPattern(*pricing.unit);
  context.ExpectMemory(*pricing.gpu, pattern);
  const ProgramTiming timing(*record.program, record.leaf.get(), pricing.datapath);
  context.ExpectUnitWarps(*pricing.gpu, pattern, timing.loop.return_count(), PassCostsOf(timing));
}

AccessPattern RtUnitAccessPattern(const RtUnitParams& unit) {
  AccessPattern p;
  p.warps_per_wave = unit.warp_buffer_warps;
  p.coalesced = false;
  return p;
}

std::uint64_t ProgramStoreMicroOps(const ProgramTiming& timing) {
  std::uint64_t n = 0;
  for (const SectionTiming* s : {&timing.prologue, &timing.loop, &timing.epilogue, &timing.leaf})
    for (const LoweredOp& op : s->ops()) n += !op.dropped;
  return n;
}

BatchCost PriceOnRtUnit(const KernelRecord& record, PricingContext& context, const RtUnitPricing& pricing,
                        const std::string& backend_name) {
  const GpuParams& gpu = *pricing.gpu;
  const RtUnitParams& unit = *pricing.unit;
  const EnergyParams& energy = *pricing.energy;
  const ProgramTiming timing(*record.program, record.leaf.get(), pricing.datapath);
  const AccessPattern pattern = RtUnitAccessPattern(unit);
  const auto memory = context.Memory(gpu, pattern);

  const RayPassCosts costs = PassCostsOf(timing);
  const int variants = timing.loop.return_count() + 1;  // exit variants: 0 = no exit, 1 + j = RETURN_IF j

  const std::size_t n = record.query_count();
  const std::size_t warps = WarpCount(record, gpu);
  const std::uint64_t intake_per_cycle =
      static_cast<std::uint64_t>(unit.intersection_unit_sets) * unit.threads_accepted_per_cycle_per_set;
  const std::vector<std::vector<std::uint32_t>> sm_warps = WarpsBySm(warps, gpu);
  std::vector<std::vector<std::uint64_t>> sm_warp_cycles(gpu.sms);
  std::vector<std::vector<std::uint64_t>> sm_variant_passes(gpu.sms, std::vector<std::uint64_t>(variants, 0));
  std::vector<std::uint64_t> sm_threads(gpu.sms, 0);
  // One pass over the queries, shared with the other units pricing this
  // record (rt_warp_cycles.h): a ray record's exit per query prices a query
  // in O(1), any other record's exit profile in O(its variants).
  const auto unit_warps = context.UnitWarps(gpu, pattern, variants - 1, costs);
  // A full warp's intake, divided once: only a launch's last warp may be
  // partial.
  const std::uint64_t full_warp_intake = CeilDiv(static_cast<std::uint64_t>(gpu.warp_size), intake_per_cycle);
  for (int sm = 0; sm < gpu.sms; ++sm) {
    sm_warp_cycles[sm].reserve(sm_warps[sm].size());
    for (std::uint32_t w : sm_warps[sm]) {
      const std::size_t lo = static_cast<std::size_t>(w) * gpu.warp_size;
      const std::size_t threads = std::min(n, lo + gpu.warp_size) - lo;
      const std::uint64_t intake =
          threads == static_cast<std::size_t>(gpu.warp_size) ? full_warp_intake : CeilDiv(threads, intake_per_cycle);
      sm_threads[sm] += threads;
      sm_warp_cycles[sm].push_back(intake + unit_warps->slowest[w]);
    }
    std::copy_n(unit_warps->sm_passes.begin() + static_cast<long>(sm) * variants, variants,
                sm_variant_passes[sm].begin());
  }

  BatchCost cost = ModelledBatchCost(backend_name, record, gpu, *memory);

  Tally total;
  std::uint64_t busiest = 0;
  for (int sm = 0; sm < gpu.sms; ++sm) {
    Tally t;
    t.Add(timing.once(), sm_threads[sm], energy);
    for (int v = 0; v < variants; ++v)
      t.Add(timing.loop.Cost(v == 0 ? kNoExit : static_cast<std::uint8_t>(v - 1)), sm_variant_passes[sm][v], energy);
    // The bounds of this unit; the largest sets its time.
    std::uint64_t cycles = Makespan(sm_warp_cycles[sm], unit.warp_buffer_warps);
    std::string bound = "latency (warp buffer)";
    auto consider = [&](std::uint64_t c, const std::string& what) {
      if (c > cycles) {
        cycles = c;
        bound = what;
      }
    };
    for (int u = 0; u < kOpUnitCount; ++u)
      consider(CeilDiv(t.unit_slots[u], static_cast<std::uint64_t>(unit.intersection_unit_sets) *
                                            static_cast<std::uint64_t>(unit.op_units_per_kind_per_set)),
               std::string("op unit ") + OpUnitName(static_cast<OpUnit>(u)));
    consider(CeilDiv(memory->sm_sector_requests[sm], static_cast<std::uint64_t>(unit.sector_requests_per_cycle)),
             "L1 requests");
    consider(CeilDiv(sm_threads[sm], intake_per_cycle), "thread intake");
    if (cycles >= busiest) {
      busiest = cycles;
      cost.bound = bound;
    }
    for (int i = 0; i < kOpcodeCount; ++i) total.executed[i] += t.executed[i];
    total.hops += t.hops;
    total.predicated += t.predicated;
    total.ctrl += t.ctrl;
    total.pushes += t.pushes;
    total.micro_ops += t.micro_ops;
    total.arithmetic_joules += t.arithmetic_joules;
  }
  FinishKernelCycles(cost,
                     pricing.launch_cycles_besides_program +
                         pricing.program_config_cycles_per_micro_op * ProgramStoreMicroOps(timing),
                     busiest, gpu);
  for (int i = 0; i < kOpcodeCount; ++i) cost.micro_ops[i] = total.executed[i];
  cost.predicated_off_micro_ops = total.predicated;
  cost.interconnect_hops = total.hops;
  cost.ctrl_exits = total.ctrl;
  cost.nodes_counted = total.pushes;
  cost.energy_joules = total.arithmetic_joules +
                       Sram8kbJoules(total.micro_ops * energy.rt_packet_accesses_per_micro_op +
                                         total.hops * energy.rt_packet_accesses_per_hop +
                                         total.predicated * energy.rt_packet_accesses_per_predicated_op +
                                         static_cast<double>(n) * energy.rt_warp_buffer_accesses_per_thread,
                                     energy) +
                       MemoryEnergyJoules(memory->totals, gpu, energy);
  return cost;
}

}  // namespace rc
