#include "workloads/carribot/carribot_report.h"

#include "backends/scheduler/scheduler_cli.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "traces/csv_table.h"

namespace rc {
namespace {

// "ttaplus-p" -> "ttaplus_p": column names stay identifiers.
std::string ColumnSafe(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

CsvCell Maybe(bool present, double value) { return present ? CsvCell(value) : CsvCell::Empty(); }

// Query columns, kernel columns and (when priced) pricing columns of one row.
struct RowWriter {
  CsvTable& table;
  const CarribotResult& result;
  std::size_t iteration = 0;  // ledger iteration of the next row
  double cum_policy = 0.0;

  void Add(CsvTable::Row& row, const KernelWork& kernel, const LedgerIteration* pricing) {
    row.Set("kernel_launches", kernel.launches)
        .Set("kernel_queries", kernel.queries)
        .Set("nodes_per_query", Maybe(kernel.queries > 0, kernel.NodesPerQuery()));
    if (result.priced) {
      const LedgerSummary& l = result.pricing;
      row.Set("backend", pricing->backend).Set("switched", static_cast<int>(pricing->switched));
      for (std::size_t b = 0; b < l.backends.size(); ++b)
        row.Set("cycles_" + ColumnSafe(l.backends[b]),
                pricing->priced ? static_cast<double>(pricing->costs[b].cycles) : 0.0);
      cum_policy += pricing->chosen_cycles;
      row.Set("energy_j", pricing->chosen_energy_j)
          .Set("cum_cycles_policy", cum_policy)
          .Set("cum_cycles_oracle", l.oracle_cumulative_cycles.at(iteration))
          .Set("oracle_backend", l.oracle_choice.at(iteration));
    }
    ++iteration;
    table.AddRow(row);
  }
};

}  // namespace

void WriteCarribotTimeline(const std::string& path, const std::vector<CarribotQuery>& queries,
                           const CarribotResult& result) {
  std::vector<std::string> columns = {"scenario",
                                      "bucket",
                                      "sx",
                                      "sy",
                                      "gx",
                                      "gy",
                                      "path_length_cells",
                                      "path_length_m",
                                      "optimal_length_cells",
                                      "turns",
                                      "expanded",
                                      "collision_queries",
                                      "kernel_launches",
                                      "kernel_queries",
                                      "nodes_per_query",
                                      "wall_s",
                                      "status"};
  if (result.priced) {
    columns.push_back("backend");
    columns.push_back("switched");
    for (const std::string& b : result.pricing.backends) columns.push_back("cycles_" + ColumnSafe(b));
    for (const char* c : {"energy_j", "cum_cycles_policy", "cum_cycles_oracle", "oracle_backend"}) columns.push_back(c);
  }
  CsvTable table(path, columns);
  RowWriter writer{table, result};
  if (result.has_setup) {
    CsvTable::Row row = table.NewRow();
    for (const char* c : {"scenario", "bucket", "sx", "sy", "gx", "gy", "path_length_cells", "path_length_m",
                          "optimal_length_cells", "turns", "expanded"})
      row.Set(c, CsvCell::Empty());
    row.Set("collision_queries", result.setup_kernel.queries).Set("wall_s", result.setup_wall_s).Set("status", "setup");
    writer.Add(row, result.setup_kernel, &result.setup_pricing);
  }
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const CarribotQuery& q = queries[i];
    const CarribotRow& r = result.rows.at(i);
    const PlanResult& p = r.result;
    CsvTable::Row row = table.NewRow();
    row.Set("scenario", q.index)
        .Set("bucket", q.bucket ? CsvCell(*q.bucket) : CsvCell::Empty())
        .Set("sx", q.start.x)
        .Set("sy", q.start.y)
        .Set("gx", q.goal.x)
        .Set("gy", q.goal.y)
        .Set("path_length_cells", Maybe(p.found(), p.length_cells))
        .Set("path_length_m", Maybe(p.found(), p.length_m))
        .Set("optimal_length_cells", q.optimal_length ? CsvCell(*q.optimal_length) : CsvCell::Empty())
        .Set("turns", p.turns)
        .Set("expanded", p.expanded)
        .Set("collision_queries", p.collision_queries)
        .Set("wall_s", p.wall_s)
        .Set("status", ToString(p.status));
    writer.Add(row, r.kernel, &r.pricing);
  }
  table.Commit();
}

void PrintCarribotPricing(std::ostream& out, const CarribotResult& result, const CarribotSettings& s) {
  if (!result.priced) return;
  const LedgerSummary& l = result.pricing;
  auto emit = [&out](const char* format, const auto&... args) {
    out << fmt::format(fmt::runtime(format), args...) << '\n';
  };
  KernelWork total = result.setup_kernel;
  for (const CarribotRow& r : result.rows) {
    total.launches += r.kernel.launches;
    total.queries += r.kernel.queries;
    total.node_visits += r.kernel.node_visits;
  }
  emit("collision kernel        {} launches, {} OBB queries, {:.1f} nodes per query",
       static_cast<unsigned long long>(total.launches), static_cast<unsigned long long>(total.queries),
       total.NodesPerQuery());
  PrintLedgerSummary(out, l, s.ledger, s.backend_params.gpu.core_clock_hz, "launch", "tree nodes per kernel query");
  double host_s = result.setup_wall_s;
  for (const CarribotRow& r : result.rows) host_s += r.result.wall_s;
  // The cost models' own time; the planner's set-up includes what recording
  // adds to the kernel's pass (docs/carribot_performance.md measures both).
  emit("pricing host time       {:.3f} s in the cost models ({:.2f}x the planner's own, recording included there)",
       result.pricing_wall_s,
       host_s > 0 ? result.pricing_wall_s / host_s : 0.0);
}

}  // namespace rc
