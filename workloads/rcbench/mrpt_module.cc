// The body of librcbench_mrpt.so: the MRPT adapters behind one table
// (mrpt_module_api.h).
#include "workloads/rcbench/mrpt_module_api.h"

#include "workloads/delibot/mrpt/mrpt_localizer.h"

extern "C" __attribute__((visibility("default"))) const rc::MrptModuleApi* rc_mrpt_module_api() {
  static const rc::MrptModuleApi api = [] {
    rc::MrptModuleApi a;
    a.load_gridmap = [](const std::string& path, const rc::ProbabilityThresholds& thresholds) {
      return rc::LoadMrptGridmap(path, thresholds);
    };
    a.load_simplemap = [](const std::string& path, double resolution_m, const rc::ProbabilityThresholds& thresholds) {
      return rc::LoadMrptSimplemap(path, resolution_m, thresholds);
    };
    a.describe_grid_map = [](const rc::MrptGridMap& map) { return rc::DescribeMrptGridMap(map); };
    a.read_rawlog = [](const std::string& path, const rc::RawlogReadOptions& options, rc::TraceReadStats* stats) {
      return rc::ReadMrptRawlog(path, options, stats);
    };
    a.run_delibot = [](const rc::OccupancyGrid& grid, rc::ScanSource& scans, const std::vector<rc::Pose2>* ground_truth,
                       const rc::DelibotSettings& settings, const rc::ProgressCallback& progress,
                       const rc::RowCallback& on_row) {
      return rc::RunMrptDelibot(grid, scans, ground_truth, settings, progress, on_row);
    };
    a.settings_json = [](const rc::DelibotSettings& settings) { return rc::MrptSettingsJson(settings); };
    return a;
  }();
  return &api;
}
