#include "workloads/delibot/mrpt/delibot_engine.h"

#include "common/input_error.h"
#include "workloads/delibot/mrpt/mrpt_localizer.h"

namespace rc {

DelibotEngine ParseDelibotEngine(const std::string& name) {
  if (name == "ours") return DelibotEngine::kOurs;
  if (name == "mrpt") return DelibotEngine::kMrpt;
  throw UsageError("unknown engine '" + name + "' (expected ours or mrpt)");
}

std::string ToString(DelibotEngine engine) { return engine == DelibotEngine::kOurs ? "ours" : "mrpt"; }

DelibotResult RunDelibotEngine(DelibotEngine engine, const OccupancyGrid& grid, const SensorTrace& trace,
                               const std::vector<Pose2>* ground_truth, const DelibotSettings& settings,
                               const ProgressCallback& progress, const RowCallback& on_row) {
  InMemoryScanSource scans(trace);
  return RunDelibotEngine(engine, grid, scans, ground_truth, settings, progress, on_row);
}

DelibotResult RunDelibotEngine(DelibotEngine engine, const OccupancyGrid& grid, ScanSource& scans,
                               const std::vector<Pose2>* ground_truth, const DelibotSettings& settings,
                               const ProgressCallback& progress, const RowCallback& on_row) {
  if (engine == DelibotEngine::kOurs) return RunDelibot(grid, scans, ground_truth, settings, progress, on_row);
  return RunMrptDelibot(grid, scans, ground_truth, settings, progress, on_row);
}

nlohmann::json DelibotEngineSummaryJson(DelibotEngine engine, const DelibotResult& result,
                                        const DelibotSettings& settings, const DelibotProvenance& provenance) {
  nlohmann::json json = DelibotSummaryJson(result, settings, provenance);
  json["engine"] = ToString(engine);
  if (engine == DelibotEngine::kMrpt) {
    json["config"]["mrpt"] = MrptSettingsJson(settings);
    // MRPT traces its own rays: our ray caster did not run.
    json["config"]["ray_caster"] = nullptr;
  }
  return json;
}

}  // namespace rc
