#pragma once
// One CarriBot run: a set of start/goal queries planned on one map, with the
// footprint's collision checks on the collision kernel, every kernel launch
// recorded and priced on every modelled backend (shadow costing, DESIGN.md),
// and a scheduler policy choosing the backend that "ran" (BackendLedger).
//
// Ledger iterations:
//  - precomputed mode with the kernel: one set-up iteration that fills the
//    configuration space (one query per cell and heading, in launches of up
//    to ConfigurationSpace::kDefaultMaxBatch poses), then one per query with
//    no kernel work (the planner reads the configuration space);
//  - per-expansion mode with the kernel: one iteration per query, holding
//    one launch per A* expansion (its successors' end poses);
//  - point robot or the rasterized checker: no kernel, nothing priced.
// Functional results (paths, expansions, collision queries) do not depend
// on the policy or on the backend: the kernel runs once on the host, and the
// backends only price what it did.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "backends/backend_params.h"
#include "backends/scheduler/backend_ledger.h"
#include "maps/occupancy_grid.h"
#include "workloads/carribot/grid_planner.h"

namespace rc {

enum class FootprintCheckerKind { kKernel, kRasterized };
// "kernel" | "rasterized"; throws std::invalid_argument otherwise.
FootprintCheckerKind ParseFootprintCheckerKind(const std::string& name);
const char* ToString(FootprintCheckerKind kind);

struct CarribotSettings {
  PlannerOptions planner;
  // Footprint robots only; a point robot checks cells directly.
  FootprintCheckerKind checker = FootprintCheckerKind::kKernel;
  bool price_backends = true;  // needs the kernel checker
  BackendParameters backend_params;
  LedgerOptions ledger;
};

struct CarribotQuery {
  long index = 0;  // scenario index (0 for an ad-hoc query)
  std::optional<int> bucket;
  GridPose start, goal;
  std::optional<double> optimal_length;  // cells, from a .scen file
  std::string origin;                    // for messages: "scenario 12 (line 14)"
};

// Kernel work of one ledger iteration.
struct KernelWork {
  std::uint64_t launches = 0;
  std::uint64_t queries = 0;      // OBB queries the kernel answered
  std::uint64_t node_visits = 0;  // tree node fetches
  double NodesPerQuery() const { return queries ? static_cast<double>(node_visits) / queries : 0.0; }
};

struct CarribotRow {
  PlanResult result;
  KernelWork kernel;
  bool priced = false;
  LedgerIteration pricing;  // valid when priced
};

struct CarribotResult {
  std::vector<CarribotRow> rows;  // one per query, in order
  bool has_setup = false;         // precomputed configuration space on the kernel
  KernelWork setup_kernel;
  double setup_wall_s = 0.0;      // planner set-up (state space, configuration space)
  LedgerIteration setup_pricing;  // valid when has_setup && priced
  bool priced = false;
  LedgerSummary pricing;        // valid when priced
  double pricing_wall_s = 0.0;  // host time spent pricing
  double turn_cost_cells = 0.0;
  int heading_count = 0;
};

using CarribotProgress = std::function<void(std::size_t done, std::size_t total)>;

// Throws UsageError for invalid settings. With several queries the paths
// are dropped (memory) unless keep_paths. PlanResult::wall_s excludes the
// time spent pricing (pricing_wall_s).
CarribotResult RunCarribot(const OccupancyGrid& grid, const std::vector<CarribotQuery>& queries,
                           const CarribotSettings& settings, bool keep_paths = false,
                           const CarribotProgress& progress = {});

}  // namespace rc
