#pragma once
// The first-order cost model of a TTA+ / RoboCore unit (one per SM),
// shared by the ttaplus, ttaplus-p, ttaplus-cr and robocore backends, which
// differ in the datapath their programs are timed on (section_timing.h) and
// in their launch.
//
// Per query (one thread): latency = the once-per-query sections + for each
// node, its loop pass with the exit the record gives (section costs already
// hold micro-op latencies, interconnect hops and the early-exit mode) + its
// node fetches' memory latency (memory_replay.h, per-thread pattern).
// Per warp: its slowest thread, plus the cycles the unit needs to take in
// its threads (artifact: 4 sets x 2 threads per cycle). A warp ends with its
// slowest thread (artifact).
// Per unit: the warps of its SM pass through the warp buffer (4 slots) in
// order: the makespan of that list schedule is the latency bound. The unit
// also cannot beat its throughput bounds: every OP unit type exists once
// per intersection unit set and takes one micro-op per initiation interval;
// L1 takes one sector request per cycle; the thread intake rate. The unit's
// time is the largest of these; the kernel's is the launch plus the slowest
// unit, or DRAM bandwidth if that is slower.
//
// Left out: queueing when several bounds are close (the max() is optimistic
// there; function_unit_simulator.h shows the effect on small cases), MSHR
// limits (64 per unit in the artifact; the ray-cast kernels have at most 128
// threads in flight per unit, each with one outstanding fetch), and the SM
// issuing the trace instructions (the RT kernel's SIMT part is a few
// instructions per ray).
#include "backends/backend.h"
#include "robocore/section_timing.h"

namespace rc {

struct RtUnitPricing {
  const RtUnitParams* unit = nullptr;
  const GpuParams* gpu = nullptr;
  const EnergyParams* energy = nullptr;
  DatapathConfig datapath;
  // The launch: these cycles, plus writing the program (as lowered for
  // `datapath`) into every unit's store at this many cycles per micro-op.
  std::uint64_t launch_cycles_besides_program = 0;
  std::uint64_t program_config_cycles_per_micro_op = 0;
};

BatchCost PriceOnRtUnit(const KernelRecord& record, PricingContext& context, const RtUnitPricing& pricing,
                        const std::string& backend_name);

// Tells the context what PriceOnRtUnit will ask of it for this record (its
// memory replay, and PricingContext::ExpectUnitWarps), so
// that the replay runs beside the other backends' and the units pricing one
// record share one pass over its queries. Prices do not depend on it.
void AnnounceRtUnit(const KernelRecord& record, PricingContext& context, const RtUnitPricing& pricing);

// What TTA+ and RoboCore backends share: each says how its unit prices a
// record (UnitPricing), and both announce and price through the unit
// model the same way.
class RtUnitBackend : public Backend {
 public:
  void AnnouncePricing(const KernelRecord& record, PricingContext& context) const final {
    AnnounceRtUnit(record, context, UnitPricing(record));
  }

 protected:
  BatchCost DoPrice(const KernelRecord& record, PricingContext& context) const final {
    return PriceOnRtUnit(record, context, UnitPricing(record), specs().name);
  }
  // The unit, its datapath and the record's launch.
  virtual RtUnitPricing UnitPricing(const KernelRecord& record) const = 0;
};

// Access pattern of the RT units: per-thread requests, warp-buffer waves.
AccessPattern RtUnitAccessPattern(const RtUnitParams& unit);

// Micro-ops a program occupies in a unit's program store on this datapath
// (after lowering), for the launch's program configuration.
std::uint64_t ProgramStoreMicroOps(const ProgramTiming& timing);

}  // namespace rc
