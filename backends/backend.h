#pragma once
// A backend runs a batch of kernel queries and says what the batch cost on
// the hardware it models. The interface is narrow (OMPL / Ceres style):
// create by name, read the capabilities as plain data, price a recorded
// batch, or run one. Every backend returns exactly the CPU reference's
// functional results; they differ only in cost.
//
//   auto simt = Backend::Create("simt", params);
//   KernelRecord record;
//   CastRayBatchRecorded(scene, batch, hits, record);   // run once...
//   BatchCost cost = simt->Price(record);               // ...price many times
//
// Names: cpu (reference, no cost model), simt, ttaplus, ttaplus-p,
// ttaplus-cr, robocore.
#include <array>
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "backends/backend_params.h"
#include "backends/memory_replay.h"
#include "backends/pricing_context.h"
#include "robocore/kernel_record.h"
#include "robocore/ray_batch.h"
#include "robocore/robocore_api.h"

namespace rc {

// What a backend is and can do, as plain data (instead of dynamic_cast).
struct BackendSpecs {
  std::string name;
  std::string description;
  bool has_cost_model = false;
  bool has_rt_unit = false;                         // TTA+ / RoboCore intersection units
  bool has_sact_units = false;                      // RoboCore's chained SACT units
  EarlyExitMode early_exit = EarlyExitMode::kNone;  // meaningful with has_rt_unit
  std::vector<StepProgramKind> step_programs;       // the kernels it prices
  double clock_hz = 0;                              // the modelled clock its cycles count (0: none)
  int sms = 0;
};

// What one batch cost. Cycles are core cycles at clock_hz and include the
// launch; energy is dynamic energy only.
struct BatchCost {
  std::string backend;
  bool modelled = false;    // false for the cpu reference
  double host_seconds = 0;  // wall time of Run's functional work (0 from Price)
  std::uint64_t queries = 0;
  std::uint64_t nodes = 0;
  std::uint64_t cycles = 0;
  std::uint64_t launch_cycles = 0;
  double clock_hz = 0;
  double seconds = 0;  // cycles / clock_hz
  double energy_joules = 0;
  double simt_efficiency = std::numeric_limits<double>::quiet_NaN();  // SIMT only
  MemoryCounters memory;                                              // 32-byte sector requests, L1/L2/DRAM
  std::array<std::uint64_t, kOpcodeCount> micro_ops{};                // executed, by type
  std::uint64_t predicated_off_micro_ops = 0;
  std::uint64_t interconnect_hops = 0;
  std::uint64_t ctrl_exits = 0;           // RoboCore: CTRL axis checks
  std::uint64_t warp_instructions = 0;    // SIMT
  std::uint64_t thread_instructions = 0;  // SIMT
  std::uint64_t nodes_counted = 0;        // PUSH counter of nodes visited
  std::string bound;                      // what limited the busiest SM
  std::string l1_model;
  std::string l2_model;

  // Adds another launch's cost (every count and time; SIMT efficiency as
  // the issued-instruction-weighted mean). The descriptive fields (backend,
  // bound, models, clock) stay this one's.
  BatchCost& operator+=(const BatchCost& more);
  // This cost times `factor` (>= 0): every count and time, counts rounded
  // to the nearest integer; SIMT efficiency and the descriptive fields
  // unchanged. For launches priced as the mean of others
  // (BackendLedger::AddLaunchesLike).
  BatchCost ScaledBy(double factor) const;
};

void PrintBatchCost(std::ostream& out, const BatchCost& cost);

class Backend {
 public:
  virtual ~Backend() = default;
  // Throws std::invalid_argument for an unknown name or invalid parameters.
  static std::unique_ptr<Backend> Create(const std::string& name, const BackendParameters& params);
  static std::vector<std::string> Names();          // all, cpu first
  static std::vector<std::string> ModelledNames();  // all but cpu

  virtual const BackendSpecs& specs() const = 0;

  // Tells `context` what Price(record, context) will ask of it, so that
  // work several backends share is done once for all (PriceAll announces
  // every backend before pricing any). Prices do not depend on it; the
  // default announces nothing.
  virtual void AnnouncePricing(const KernelRecord& /*record*/, PricingContext& /*context*/) const {}

  // Prices a recorded batch. The context lets backends that price the same
  // record share work (the memory replay); results do not depend on it.
  BatchCost Price(const KernelRecord& record) const;
  BatchCost Price(const KernelRecord& record, PricingContext& context) const;

  // Runs the batch: functional hits (identical to CastRayBatch) and cost.
  virtual BatchCost Run(const RayCastScene& scene, const RayBatch& batch, std::vector<RayHit>& hits) const;

  // Runs a collision batch (robot-link OBBs against a box tree) through the
  // RoboCore API's CheckCollisions: functional results identical to
  // CollideBatch on every backend (the host kernel answers; the backend
  // prices its recorded SACT traversal), and the cost. Throws as
  // CheckCollisions does.
  template <typename Scalar>
  BatchCost RunCollisions(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                          std::vector<CollisionResult>& results, const CollisionOptions<Scalar>& options = {}) const;

 protected:
  virtual BatchCost DoPrice(const KernelRecord& record, PricingContext& context) const = 0;
};

// Prices one record on several backends, sharing their common work.
std::vector<BatchCost> PriceAll(const std::vector<const Backend*>& backends, const KernelRecord& record);

}  // namespace rc
