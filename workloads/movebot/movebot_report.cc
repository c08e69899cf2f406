#include "workloads/movebot/movebot_report.h"

#include "backends/scheduler/scheduler_cli.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <iomanip>
#include <ostream>
#include <unistd.h>

#include <ompl/base/PlannerStatus.h>
#include <ompl/config.h>

#include "backends/scheduler/scheduler_cli.h"
#include "common/atomic_file.h"
#include "traces/csv_table.h"

namespace rc {
namespace {

// "ttaplus-p" -> "ttaplus_p": column names stay identifiers.
std::string ColumnSafe(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

CsvCell FiniteOrEmpty(double v) { return std::isfinite(v) ? CsvCell(v) : CsvCell::Empty(); }

double CostOf(const LedgerIteration& it, std::size_t b) {
  return it.priced ? static_cast<double>(it.costs[b].cycles) : 0.0;
}

// Debian's ompl/config.h leaves OMPL_VERSION empty; the numbers are set.
std::string OmplVersion() {
  return std::to_string(OMPL_MAJOR_VERSION) + "." + std::to_string(OMPL_MINOR_VERSION) + "." +
         std::to_string(OMPL_PATCH_VERSION);
}

}  // namespace

void WriteMoveBotTimeline(const std::string& path, const MoveBotResult& result) {
  std::vector<std::string> columns = {"row",
                                      "iterations",
                                      "samples",
                                      "time_s",
                                      "tree_states",
                                      "collision_configurations",
                                      "collision_queries",
                                      "collision_nodes_per_query",
                                      "self_collision_tests",
                                      "self_collisions",
                                      "nn_queries",
                                      "nn_nodes_per_query",
                                      "best_cost_rad"};
  const std::vector<std::string>& backends = result.collision_pricing.backends;
  if (result.priced) {
    columns.push_back("backend_collision");
    columns.push_back("backend_nn");
    for (const std::string& b : backends) columns.push_back("cycles_" + ColumnSafe(b));
    columns.push_back("cycles_chosen");
    columns.push_back("energy_j");
  }
  CsvTable table(path, columns);
  for (const MoveBotRow& r : result.rows) {
    std::vector<CsvCell> cells = {
        r.row,
        r.iterations,
        r.samples,
        r.time_s,
        r.tree_states,
        r.collision.configurations,
        r.collision.queries,
        r.collision.queries ? CsvCell(static_cast<double>(r.collision.nodes) / r.collision.queries) : CsvCell::Empty(),
        result.self_collision_checked ? CsvCell(r.collision.self_tests) : CsvCell::Empty(),
        result.self_collision_checked ? CsvCell(r.collision.self_collisions) : CsvCell::Empty(),
        r.nn.queries,
        r.nn.has_nodes && r.nn.queries ? CsvCell(static_cast<double>(r.nn.nodes_visited) / r.nn.queries)
                                       : CsvCell::Empty(),
        FiniteOrEmpty(r.best_cost_rad)};
    if (result.priced) {
      cells.emplace_back(r.collision_pricing.backend);
      cells.emplace_back(r.nn_pricing.backend);
      for (std::size_t b = 0; b < backends.size(); ++b)
        cells.emplace_back(CostOf(r.collision_pricing, b) + CostOf(r.nn_pricing, b));
      cells.emplace_back(r.collision_pricing.chosen_cycles + r.nn_pricing.chosen_cycles);
      cells.emplace_back(r.collision_pricing.chosen_energy_j + r.nn_pricing.chosen_energy_j);
    }
    table.AddRow(cells);
  }
  table.Commit();
}

void WriteAnytimeCurve(const std::string& path, const MoveBotResult& result) {
  CsvTable table(path, {"time_s", "iterations", "best_cost_rad"});
  for (const MoveBotRow& r : result.rows) table.AddRow({r.time_s, r.iterations, FiniteOrEmpty(r.best_cost_rad)});
  table.Commit();
}

void WriteArmPath(const std::string& path, const MoveBotResult& result) {
  std::vector<std::string> columns;
  for (int j = 1; j <= kArmJoints; ++j) columns.push_back("q" + std::to_string(j) + "_rad");
  CsvTableOptions options;
  options.significant_digits = 17;  // joint angles round-trip exactly
  CsvTable table(path, columns, options);
  for (const ArmConfiguration& q : result.path) table.AddRow(std::vector<CsvCell>(q.begin(), q.end()));
  table.Commit();
}

void WriteOmplBenchmarkLog(const std::string& path, const MoveBotResult& result, const OmplLogContext& context) {
  namespace ob = ompl::base;
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << std::setprecision(17);
  char host[256] = "unknown";
  gethostname(host, sizeof host - 1);
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%S", std::gmtime(&now));
  out << "OMPL version " << OmplVersion() << "\n";
  out << "Experiment " << context.experiment << "\n";
  out << "Running on " << host << "\n";
  out << "Starting at " << date << "\n";
  out << "<<<|\n" << context.setup << "\n|>>>\n";
  out << "<<<|\n|>>>\n";  // no CPU information
  out << context.seed << " is the random seed\n";
  out << context.time_limit_s << " seconds per run\n";
  out << "-1 MB per run\n";
  out << "1 runs per planner\n";
  out << result.planning_s << " seconds spent to collect the data\n";
  out << "1 enum types\nstatus";
  for (int s = 0; s < ob::PlannerStatus::TYPE_COUNT; ++s)
    out << '|' << ob::PlannerStatus(static_cast<ob::PlannerStatus::StatusType>(s)).asString();
  out << "\n1 planners\ngeometric_" << result.planner_name << "\n0 common properties\n";

  const bool solved = result.status != MoveBotStatus::kNone;
  const int status = result.status == MoveBotStatus::kExact         ? ob::PlannerStatus::EXACT_SOLUTION
                     : result.status == MoveBotStatus::kApproximate ? ob::PlannerStatus::APPROXIMATE_SOLUTION
                                                                    : ob::PlannerStatus::TIMEOUT;
  std::uint64_t collision_queries = 0, nn_queries = 0;
  for (const MoveBotRow& r : result.rows) {
    collision_queries += r.collision.queries;
    nn_queries += r.nn.queries;
  }
  auto real = [](double v) { return std::isfinite(v) ? std::to_string(v) : std::string(); };
  // Alphabetical, as ompl::tools::Benchmark writes them.
  const std::vector<std::pair<std::string, std::string>> props = {
      {"approximate solution BOOLEAN", std::to_string(result.status == MoveBotStatus::kApproximate)},
      {"best cost REAL", real(result.path_cost_rad)},
      {"collision queries INTEGER", std::to_string(collision_queries)},
      {"correct solution BOOLEAN", std::to_string(solved && context.verified)},
      {"iterations INTEGER", std::to_string(result.iterations)},
      {"nn queries INTEGER", std::to_string(nn_queries)},
      {"solution difference REAL", real(result.goal_distance_rad)},
      {"solution length REAL", real(result.path_cost_rad)},
      {"solution segments INTEGER", std::to_string(result.path.empty() ? 0 : result.path.size() - 1)},
      {"solved BOOLEAN", std::to_string(result.status == MoveBotStatus::kExact)},
      {"status ENUM", std::to_string(status)},
      {"time REAL", real(result.planning_s)},
  };
  out << props.size() << " properties for each run\n";
  for (const auto& p : props) out << p.first << "\n";
  out << "1 runs\n";
  for (const auto& p : props) out << p.second << "; ";
  out << "\n3 progress properties for each run\nbest cost REAL\niterations INTEGER\ntime REAL\n1 runs\n";
  for (const MoveBotRow& r : result.rows)
    out << (std::isfinite(r.best_cost_rad) ? std::to_string(r.best_cost_rad) : std::string("inf")) << ','
        << r.iterations << ',' << r.time_s << ",;";
  out << "\n.\n";
  file.Commit();
}

void PrintMoveBotSummary(std::ostream& out, const MoveBotResult& result, const MoveBotSettings& settings) {
  out << std::setprecision(6);
  std::uint64_t configurations = 0, queries = 0, nodes = 0, nn_queries = 0, nn_nodes = 0;
  std::uint64_t self_tests = 0, self_collisions = 0, self_only = 0;
  bool nn_has_nodes = false;
  for (const MoveBotRow& r : result.rows) {
    configurations += r.collision.configurations;
    queries += r.collision.queries;
    nodes += r.collision.nodes;
    self_tests += r.collision.self_tests;
    self_collisions += r.collision.self_collisions;
    self_only += r.collision.self_only;
    nn_queries += r.nn.queries;
    nn_nodes += r.nn.nodes_visited;
    nn_has_nodes = nn_has_nodes || r.nn.has_nodes;
  }
  out << "planner                 " << result.planner_name << " (OMPL " << OmplVersion() << "), seed " << settings.seed
      << ", " << result.iterations << " iterations in " << result.planning_s << " s, " << result.rows.size()
      << " timeline rows\n";
  out << "result                  " << ToString(result.status);
  if (result.status != MoveBotStatus::kNone)
    out << ", cost " << result.path_cost_rad << " rad (joint-space length), " << result.path.size() << " states";
  if (result.status == MoveBotStatus::kApproximate) out << ", " << result.goal_distance_rad << " rad short of the goal";
  out << "\ncollision kernel        " << configurations << " configurations, " << queries
      << " queries (link OBB x scene frame" << (result.self_collision_checked ? "; link pairs), " : "), ")
      << (queries ? static_cast<double>(nodes) / queries : 0.0) << " nodes per query\n";
  out << "self-collision          ";
  if (result.self_collision_checked)
    out << self_tests << " link pairs tested in the kernel (one node each, a query per configuration), "
        << self_collisions << " configurations refused (boxes grown on edges), " << self_only
        << " of them clear of the scene\n";
  else
    out << "not checked (--no-self-collision)\n";
  out << "nearest neighbours      " << ToString(settings.nn) << ", " << nn_queries << " queries";
  if (nn_has_nodes && nn_queries) out << ", " << static_cast<double>(nn_nodes) / nn_queries << " nodes per query";
  out << "\n";
  if (!result.priced) return;
  // Two kernels, two ledgers: each is scheduled and graded on its own.
  out << "collision kernel, ";
  PrintLedgerSummary(out, result.collision_pricing, settings.ledger, settings.backend_params.gpu.core_clock_hz, "batch",
                     "nodes per kernel query");
  const auto& nn_totals = result.nn_pricing.static_total_cycles;
  if (std::all_of(nn_totals.begin(), nn_totals.end(), [](double c) { return c == 0.0; })) {
    out << "nearest-neighbour kernel: no batch ran on the device (" << ToString(settings.nn) << ")\n";
    return;
  }
  out << "nearest-neighbour kernel, ";
  PrintLedgerSummary(out, result.nn_pricing, settings.ledger, settings.backend_params.gpu.core_clock_hz, "batch",
                     "nodes per NN query");
}

}  // namespace rc
