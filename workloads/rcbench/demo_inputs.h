#pragma once
// The built-in demo's inputs, made by the project's own generator and
// simulator (never copied from ../shared/data): the generated office map
// (ROS YAML + PGM) and a simulated CMU-format trace with its ground truth.
// Deterministic: the same files every time.
#include <string>
#include <vector>

#include "maps/occupancy_grid.h"
#include "traces/ground_truth_io.h"
#include "traces/sensor_trace.h"

namespace rc {

struct DemoInputs {
  OccupancyGrid grid;
  SensorTrace trace;
  std::vector<GroundTruthPose> ground_truth;
  std::string map_path, trace_path, ground_truth_path;
};

// Generates the inputs and writes them into `directory` (created if needed).
DemoInputs MakeDemoInputs(const std::string& directory);

}  // namespace rc
