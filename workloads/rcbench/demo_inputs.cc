#include "workloads/rcbench/demo_inputs.h"

#include <filesystem>

#include "maps/office_map_generator.h"
#include "maps/ros_map_io.h"
#include "traces/cmu_log_writer.h"
#include "workloads/delibot/trace_simulator.h"

namespace rc {

DemoInputs MakeDemoInputs(const std::string& directory) {
  std::filesystem::create_directories(directory);
  DemoInputs demo;
  demo.grid = GenerateOfficeMap(OfficeMapOptions{});
  SimulationOptions sim;  // defaults: seed 1, CMU laser, light clutter and drift
  sim.record_count = 400;
  const SimulatedTrace simulated = SimulateTrace(demo.grid, sim);
  demo.trace = simulated.trace;
  demo.ground_truth = simulated.ground_truth;
  demo.map_path = directory + "/office.yaml";
  demo.trace_path = directory + "/office_run.log";
  demo.ground_truth_path = directory + "/office_run.gt";
  SaveRosMap(demo.grid, demo.map_path, RosMapSaveOptions{});
  WriteCmuLog(demo.trace, demo.trace_path);
  WriteGroundTruth(demo.ground_truth_path, demo.ground_truth);
  return demo;
}

}  // namespace rc
