#include "workloads/carribot/carribot_run.h"

#include <chrono>
#include <memory>
#include <stdexcept>

#include <omp.h>

#include "backends/calibration/sact_kernel_record.h"
#include "common/input_error.h"
#include "workloads/carribot/configuration_space.h"
#include "workloads/carribot/kernel_footprint_checker.h"

namespace rc {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kSerialPricingQueries = 1024;  // launches up to 32 warps are priced on one thread
double SecondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Every launch of the kernel checker, counted and, with a ledger, recorded
// in the kernel's pass (its addresses kept for the ledger's sample of SMs,
// --replay-sms) and priced on every backend into the ledger's open
// iteration. Without a ledger nothing is recorded: the checker's own
// counters give the work. The ledger's preparation is pricing work too,
// and is timed with it.
class LaunchRecorder {
 public:
  LaunchRecorder(KernelFootprintChecker& checker, BackendLedger* ledger) : checker_(checker), ledger_(ledger) {
    if (ledger)
      checker.set_record_observer([this](const KernelRecord& record) { Record(record); }, ledger->RecordSample());
  }
  // Prepares the ledger now, with no start probe (Prepare's spread of
  // lengths: cheap for the per-expansion launches of a few queries).
  void PrepareNow(const KernelRecord& layout, std::size_t queries_per_batch) {
    const auto t0 = Clock::now();
    ledger_->Prepare(layout, queries_per_batch);
    pricing_wall_s_ += SecondsSince(t0);
  }
  // Prepares the ledger at the first launch, with that launch as the start
  // probe, then begins the ledger's iteration. For the configuration
  // space's fill: its first launch is the first batch exactly as the run
  // knows it in advance (its poses depend on the map and the footprint
  // only), and it costs nothing extra to record; Prepare's spread of
  // lengths up to 1024 nodes would instead price 65,536 queries of 512
  // nodes on average against the fill's 19 (twice the fill's node fetches,
  // measured: 41% of a priced Intel scale-1 run).
  void PrepareAtFirstLaunch(KernelRecord layout, std::size_t queries_per_batch) {
    pending_layout_ = std::move(layout);
    pending_batch_ = queries_per_batch;
    prepare_pending_ = true;
  }
  // If no launch came: prepares without a probe and begins the iteration.
  void FinishPendingPrepare() {
    const auto t0 = Clock::now();
    PreparePending(nullptr);
    pricing_wall_s_ += SecondsSince(t0);
  }
  // The work since the last call.
  KernelWork TakeWork() {
    if (!ledger_) {
      const KernelWork total{checker_.batches(), checker_.kernel_queries(), checker_.node_visits()};
      const KernelWork w{total.launches - taken_.launches, total.queries - taken_.queries,
                         total.node_visits - taken_.node_visits};
      taken_ = total;
      return w;
    }
    KernelWork w = open_;
    open_ = {};
    return w;
  }
  double pricing_wall_s() const { return pricing_wall_s_; }

 private:
  void Record(const KernelRecord& record) {
    ++open_.launches;
    open_.queries += record.query_count();
    open_.node_visits += record.total_nodes();
    const auto t0 = Clock::now();
    PreparePending(&record);
    // A per-expansion launch is a handful of queries (one warp): the cost
    // models' OpenMP loops over SMs then have nothing to share, and their
    // fork/join costs far more than the pricing (measured 60x on a loaded
    // 2-core machine). Prices do not depend on the thread count.
    const bool small = record.query_count() <= kSerialPricingQueries;
    const int threads = omp_get_max_threads();
    if (small) omp_set_num_threads(1);
    ledger_->AddLaunch(record);
    if (small) omp_set_num_threads(threads);
    pricing_wall_s_ += SecondsSince(t0);
  }

  // A pending preparation, with `probe` as the start probe (null: none),
  // then the set-up iteration begins.
  void PreparePending(const KernelRecord* probe) {
    if (!prepare_pending_) return;
    prepare_pending_ = false;
    ledger_->Prepare(pending_layout_, pending_batch_, kDefaultMaxNodesPerQuery, probe);
    ledger_->BeginIteration();
  }

  const KernelFootprintChecker& checker_;
  BackendLedger* ledger_;
  KernelWork open_;
  KernelWork taken_;  // the checker's counters at the last TakeWork (no ledger)
  double pricing_wall_s_ = 0.0;
  bool prepare_pending_ = false;
  KernelRecord pending_layout_;
  std::size_t pending_batch_ = 0;
};

// A record with the kernel's program and tree layout, for the adaptive
// threshold before the first iteration (its fetches do not matter).
KernelRecord LayoutRecord(const KernelFootprintChecker& checker) {
  CollisionOptions<double> options;
  options.sact.parallel_epsilon = 0.0;
  const CollisionBatch one = CollideBatch(checker.tree(), std::vector<Obbd>{Obbd{}}, options);
  return SactKernelRecord(one);
}

}  // namespace

FootprintCheckerKind ParseFootprintCheckerKind(const std::string& name) {
  if (name == "kernel") return FootprintCheckerKind::kKernel;
  if (name == "rasterized") return FootprintCheckerKind::kRasterized;
  throw std::invalid_argument("footprint checker '" + name + "': expected kernel or rasterized");
}

const char* ToString(FootprintCheckerKind kind) {
  return kind == FootprintCheckerKind::kKernel ? "kernel" : "rasterized";
}

CarribotResult RunCarribot(const OccupancyGrid& grid, const std::vector<CarribotQuery>& queries,
                           const CarribotSettings& settings, bool keep_paths, const CarribotProgress& progress) {
  std::string error;
  if (!settings.planner.IsValid(&error)) throw UsageError(error);
  const bool footprint = settings.planner.footprint.has_value();
  const bool on_kernel = footprint && settings.checker == FootprintCheckerKind::kKernel;
  const bool precomputed = footprint && settings.planner.footprint->check_mode == FootprintCheckMode::kPrecomputed;

  CarribotResult out;
  std::unique_ptr<KernelFootprintChecker> checker;
  std::unique_ptr<BackendLedger> ledger;
  std::unique_ptr<LaunchRecorder> recorder;
  if (on_kernel) {
    checker = std::make_unique<KernelFootprintChecker>(grid);
    if (settings.price_backends) ledger = std::make_unique<BackendLedger>(settings.backend_params, settings.ledger);
    recorder = std::make_unique<LaunchRecorder>(*checker, ledger.get());
    if (ledger) {
      // Per expansion: at most 10 successors (8 steps, 2 turns) per launch.
      if (precomputed)
        recorder->PrepareAtFirstLaunch(LayoutRecord(*checker),
                                       std::min(ConfigurationSpace::kDefaultMaxBatch,
                                                grid.cell_count() * settings.planner.footprint->heading_count));
      else
        recorder->PrepareNow(LayoutRecord(*checker), 10);
    }
  }

  // The set-up iteration (precomputed fill) begins at its first launch.
  const std::unique_ptr<GridPlanner> planner = GridPlanner::Create(grid, settings.planner, checker.get());
  out.setup_wall_s = planner->setup_wall_s();
  out.turn_cost_cells = planner->turn_cost_cells();
  out.heading_count = planner->heading_count();
  if (on_kernel && precomputed) {
    out.has_setup = true;
    if (ledger) recorder->FinishPendingPrepare();
    out.setup_kernel = recorder->TakeWork();
    out.setup_wall_s -= recorder->pricing_wall_s();
    if (ledger) out.setup_pricing = ledger->EndIteration(nullptr);
  }

  out.rows.reserve(queries.size());
  for (const CarribotQuery& q : queries) {
    if (ledger) ledger->BeginIteration();
    const double priced_before = recorder ? recorder->pricing_wall_s() : 0.0;
    CarribotRow row;
    row.result = planner->Plan(q.start, q.goal);
    if (recorder) {
      row.result.wall_s -= recorder->pricing_wall_s() - priced_before;
      row.kernel = recorder->TakeWork();
    }
    if (queries.size() > 1 && !keep_paths) row.result.path = {};
    if (ledger) {
      row.priced = true;
      row.pricing = ledger->EndIteration(nullptr);
    }
    out.rows.push_back(std::move(row));
    if (progress) progress(out.rows.size(), queries.size());
  }
  if (ledger) {
    out.priced = true;
    out.pricing = ledger->Finish();
  }
  if (recorder) out.pricing_wall_s = recorder->pricing_wall_s();
  return out;
}

}  // namespace rc
