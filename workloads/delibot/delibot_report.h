#pragma once
// DeliBot's outputs: the per-record timeline (CSV), the run summary (JSON)
// and the human summary printed at the end of a run. All units SI, named in
// the column or key.
#include <memory>
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "traces/csv_table.h"
#include "workloads/delibot/delibot_run.h"

namespace rc {

// Where the inputs came from, echoed into the summary.
struct DelibotProvenance {
  std::string map_path, map_format, map_convention;
  std::string trace_path, trace_format, ground_truth_path;
  int threads = 0;
};

// Columns: iteration, time_s, est_x_m, est_y_m, est_theta_rad, ess, rays,
// nodes, nodes_per_ray, wall_s, sensor_updated, log_mean_likelihood_nats,
// resampled, injected, injection_rejected, hypotheses_alive, particles,
// spread_m, mode_weight, consistency; with ground truth also err_xy_m,
// err_theta_rad; with backend pricing also backend, nodes_per_ray_prev,
// threshold_nodes_per_ray, switched, cycles_<backend> for every backend, simt_efficiency,
// energy_j (the chosen backend's), cum_cycles_policy, cum_cycles_<backend>,
// cum_cycles_oracle and oracle_backend.
//
// Written while the run goes: one row per record, flushed as it comes, under
// the incomplete marker of traces/csv_table.h; Finish() adds the hindsight
// oracle's two columns and puts the complete table in place. A killed run
// leaves the marked prefix (without the oracle columns).
class DelibotTimeline {
 public:
  // work_counted: false for an engine that does not report its kernel work
  // (rays and nodes are then written empty). The columns are fixed by the
  // first row (ground truth, pricing); the file opens with it.
  DelibotTimeline(std::string path, bool work_counted);
  ~DelibotTimeline();
  void Add(const DelibotRow& row);
  // Throws std::logic_error if `result` is not the run whose rows were added.
  void Finish(const DelibotResult& result);

 private:
  void Open(const DelibotRow& first);

  std::string path_;
  bool work_counted_;
  bool ground_truth_ = false;
  bool priced_ = false;
  std::vector<std::string> backends_;
  std::vector<double> cumulative_;
  double cumulative_policy_ = 0.0;
  std::unique_ptr<CsvTable> table_;
};

// The whole timeline of a finished run at once.
void WriteDelibotTimeline(const std::string& path, const DelibotResult& result);

nlohmann::json DelibotSummaryJson(const DelibotResult& result, const DelibotSettings& settings,
                                  const DelibotProvenance& provenance);
void WriteJsonFile(const std::string& path, const nlohmann::json& json);

void PrintDelibotSummary(std::ostream& out, const DelibotResult& result, const DelibotSettings& settings);

}  // namespace rc
