#pragma once
// DeliBot's outputs: the per-record timeline (CSV), the run summary (JSON)
// and the human summary printed at the end of a run. All units SI, named in
// the column or key.
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "workloads/delibot/delibot_run.h"

namespace rc {

// Where the inputs came from, echoed into the summary.
struct DelibotProvenance {
  std::string map_path, map_format, map_convention;
  std::string trace_path, trace_format, ground_truth_path;
  int threads = 0;
};

// Columns: iteration, time_s, est_x_m, est_y_m, est_theta_rad, ess, rays,
// nodes, nodes_per_ray, wall_ms, sensor_updated, log_mean_likelihood_nats,
// resampled, injected, injection_rejected, hypotheses_alive, particles,
// spread_m, mode_weight, consistency; with ground truth also err_xy_m,
// err_theta_rad; with backend pricing also backend, nodes_per_ray_prev,
// threshold, switched, cycles_<backend> for every backend, simt_efficiency,
// energy_j (the chosen backend's), cum_cycles_policy, cum_cycles_<backend>,
// cum_cycles_oracle and oracle_backend.
void WriteDelibotTimeline(const std::string& path, const DelibotResult& result);

nlohmann::json DelibotSummaryJson(const DelibotResult& result, const DelibotSettings& settings,
                                  const DelibotProvenance& provenance);
void WriteJsonFile(const std::string& path, const nlohmann::json& json);

void PrintDelibotSummary(std::ostream& out, const DelibotResult& result, const DelibotSettings& settings);

}  // namespace rc
