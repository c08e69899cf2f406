#pragma once
// MoveBot's outputs, each written only after the whole run succeeded
// (atomic files: a failed run leaves no partial output):
//   timeline CSV   one row per batch of iterations (movebot_run.h)
//   anytime CSV    best cost against planning time, one point per row
//   path file      one configuration per line, joints in rad
//   OMPL log       the benchmark log format of ompl::tools::Benchmark,
//                  readable by ompl_benchmark_statistics.py / Planner Arena
//                  (one experiment, one planner, one run, with the anytime
//                  curve as the run's progress properties)
#include <iosfwd>
#include <string>

#include "workloads/movebot/movebot_run.h"

namespace rc {

void WriteMoveBotTimeline(const std::string& path, const MoveBotResult& result);
void WriteAnytimeCurve(const std::string& path, const MoveBotResult& result);
void WriteArmPath(const std::string& path, const MoveBotResult& result);

struct OmplLogContext {
  std::string experiment = "movebot";
  std::string setup;  // free text: scene, start, goal, settings
  std::uint32_t seed = 0;
  double time_limit_s = 0;  // s, the budget (with an iteration budget: the time it took)
  bool verified = false;    // the independent check passed (path_verification.h)
};
void WriteOmplBenchmarkLog(const std::string& path, const MoveBotResult& result, const OmplLogContext& context);

void PrintMoveBotSummary(std::ostream& out, const MoveBotResult& result, const MoveBotSettings& settings);

}  // namespace rc
