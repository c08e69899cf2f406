#pragma once
// `rcbench delibot --engine ours|mrpt`: one entry point for both localizers,
// so the command line needs no MRPT header. Both return a DelibotResult and
// are reported by the same writers (delibot_report.h).
#include <string>

#include <nlohmann/json.hpp>

#include "workloads/delibot/delibot_report.h"
#include "workloads/delibot/delibot_run.h"

namespace rc {

enum class DelibotEngine { kOurs, kMrpt };

// "ours" | "mrpt"; throws UsageError otherwise.
DelibotEngine ParseDelibotEngine(const std::string& name);
std::string ToString(DelibotEngine engine);

DelibotResult RunDelibotEngine(DelibotEngine engine, const OccupancyGrid& grid, const SensorTrace& trace,
                               const std::vector<Pose2>* ground_truth, const DelibotSettings& settings,
                               const ProgressCallback& progress = {}, const RowCallback& on_row = {});
DelibotResult RunDelibotEngine(DelibotEngine engine, const OccupancyGrid& grid, ScanSource& scans,
                               const std::vector<Pose2>* ground_truth, const DelibotSettings& settings,
                               const ProgressCallback& progress = {}, const RowCallback& on_row = {});

// DelibotSummaryJson plus "engine" and, for MRPT, the MRPT settings used and
// the ones of ours it has no counterpart for.
nlohmann::json DelibotEngineSummaryJson(DelibotEngine engine, const DelibotResult& result,
                                        const DelibotSettings& settings, const DelibotProvenance& provenance);

}  // namespace rc
