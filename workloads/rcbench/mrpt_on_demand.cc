// rcbench's definitions of the MRPT adapters' entry points: each forwards
// to librcbench_mrpt.so, opened on the first call (mrpt_module_api.h). Test
// and benchmark binaries link the adapters themselves (rc::mrpt_maps,
// rc::mrpt_io, rc::mrpt_engine) instead; no binary links both.
#include "common/on_demand_module.h"
#include "workloads/delibot/mrpt/mrpt_localizer.h"
#include "workloads/rcbench/mrpt_module_api.h"

namespace rc {
namespace {

const MrptModuleApi& Module() {
  static const MrptModuleApi& api = OpenModuleApi<MrptModuleApi>("mrpt", "rc_mrpt_module_api");
  return api;
}

}  // namespace

MrptGridMap LoadMrptGridmap(const std::string& path, const ProbabilityThresholds& thresholds) {
  return Module().load_gridmap(path, thresholds);
}

MrptGridMap LoadMrptSimplemap(const std::string& path, double resolution_m, const ProbabilityThresholds& thresholds) {
  return Module().load_simplemap(path, resolution_m, thresholds);
}

std::string DescribeMrptGridMap(const MrptGridMap& map) { return Module().describe_grid_map(map); }

SensorTrace ReadMrptRawlog(const std::string& path, const RawlogReadOptions& options, TraceReadStats* stats) {
  return Module().read_rawlog(path, options, stats);
}

DelibotResult RunMrptDelibot(const OccupancyGrid& grid, ScanSource& scans, const std::vector<Pose2>* ground_truth,
                             const DelibotSettings& settings, const ProgressCallback& progress,
                             const RowCallback& on_row) {
  return Module().run_delibot(grid, scans, ground_truth, settings, progress, on_row);
}

nlohmann::json MrptSettingsJson(const DelibotSettings& settings) { return Module().settings_json(settings); }

}  // namespace rc
