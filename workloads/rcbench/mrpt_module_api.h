#pragma once
// What rcbench's MRPT module (librcbench_mrpt.so, mrpt_module.cc) offers the
// binary: every entry point of the MRPT adapters that the front end's
// dispatch code calls. rcbench itself links none of MRPT; its forwarders
// (mrpt_on_demand.cc) open the module on the first call (common/
// on_demand_module.h). The module and the binary come from one build, so
// the table passes C++ types; `size` guards against a stale module.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "maps/mrpt/mrpt_map_loader.h"
#include "traces/mrpt/mrpt_rawlog_reader.h"
#include "workloads/delibot/delibot_run.h"

namespace rc {

struct MrptModuleApi {
  std::size_t size = sizeof(MrptModuleApi);
  MrptGridMap (*load_gridmap)(const std::string& path, const ProbabilityThresholds& thresholds);
  MrptGridMap (*load_simplemap)(const std::string& path, double resolution_m, const ProbabilityThresholds& thresholds);
  std::string (*describe_grid_map)(const MrptGridMap& map);
  SensorTrace (*read_rawlog)(const std::string& path, const RawlogReadOptions& options, TraceReadStats* stats);
  DelibotResult (*run_delibot)(const OccupancyGrid& grid, ScanSource& scans, const std::vector<Pose2>* ground_truth,
                               const DelibotSettings& settings, const ProgressCallback& progress,
                               const RowCallback& on_row);
  nlohmann::json (*settings_json)(const DelibotSettings& settings);
};

}  // namespace rc

// The module's one exported symbol.
extern "C" const rc::MrptModuleApi* rc_mrpt_module_api();
