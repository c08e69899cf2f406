// `rcbench simulate`: drives a robot along a collision-free route through a
// map and writes a CMU-format laser trace plus a ground-truth file.
#include <filesystem>
#include <iostream>

#include "common/atomic_file.h"
#include "common/exit_codes.h"
#include "common/input_error.h"
#include "maps/map_loader.h"
#include "maps/office_map_generator.h"
#include "traces/cmu_log_writer.h"
#include "traces/ground_truth_io.h"
#include "workloads/delibot/free_space_route.h"
#include "workloads/delibot/trace_simulator.h"
#include "workloads/rcbench/commands.h"
#include "workloads/rcbench/map_options.h"
#include "workloads/rcbench/number_checks.h"

namespace rc {

void AddSimulateCommand(CLI::App& app) {
  struct Cli {
    std::string map_path, map_format = "auto", map_convention, output = "out/sim_run.log", ground_truth;
    double map_resolution_m = 0.0;
    MapLoadOptions map_options;  // thresholds
    bool no_noise = false;
    SimulationOptions options;
  };
  auto cli = std::make_shared<Cli>();
  SimulationOptions& o = cli->options;
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Simulate a laser trace (CMU .log) with ground truth through a map (default: the generated office)");
  CLI::Option* map = cmd->add_option(
      "--map", cli->map_path,
      "Map file: CMU .dat, RoWild .dat, ROS .yaml, MovingAI .map or an image (not MRPT's); default: the generated "
      "office map");
  // The options that describe --map mean nothing without it.
  cmd->add_option("--map-format", cli->map_format, "auto | cmu | rowild | ros | movingai | image")
      ->needs(map)
      ->capture_default_str();
  cmd->add_option("--map-convention", cli->map_convention, "CMU/RoWild .dat values: 'free' (default) or 'occupied'")
      ->needs(map);
  cmd->add_option("--map-resolution", cli->map_resolution_m,
                  "Cell size (m) for MovingAI maps (default 1) and images (required)")
      ->needs(map)
      ->check(FinitePositive());
  AddMapThresholdOptions(*cmd, cli->map_options);
  cmd->add_option("--output", cli->output, "Trace path (CMU robotdata format)")->capture_default_str();
  cmd->add_option("--ground-truth", cli->ground_truth, "Ground-truth path (default: the trace path with .gt)");
  cmd->add_option("--seed", o.seed, "Random seed for route, noise, people and kidnap (unitless)")
      ->capture_default_str();
  cmd->add_option("--records", o.record_count, "Number of laser records (count)")->capture_default_str();
  cmd->add_option("--waypoints", o.waypoint_count, "Random route waypoints (count)")->capture_default_str();
  cmd->add_option("--robot-radius", o.robot_radius_m, "Disc robot radius (m)")->capture_default_str();
  cmd->add_option("--speed", o.speed_mps, "Driving speed (m/s)")->capture_default_str();
  cmd->add_option("--turn-rate", o.turn_rate_radps, "In-place turn rate (rad/s)")->capture_default_str();
  cmd->add_option("--laser-rate", o.laser_rate_hz, "Laser records per second (Hz)")->capture_default_str();
  cmd->add_option("--laser-offset", o.geometry.offset_forward_m,
                  "Laser mount ahead of the robot centre on its heading axis (m); written into every record's laser "
                  "pose")
      ->capture_default_str();
  cmd->add_option("--range-sigma", o.range_sigma_m, "Gaussian range noise (m)")->capture_default_str();
  cmd->add_option("--short-probability", o.short_reading_probability, "Per-beam unmodelled short reading (probability)")
      ->capture_default_str();
  cmd->add_option("--dropout-probability", o.max_range_dropout_probability, "Per-beam max-range dropout (probability)")
      ->capture_default_str();
  cmd->add_option("--people", o.people_count, "Moving people discs that the laser sees (count)")->capture_default_str();
  cmd->add_option("--people-radius", o.people_radius_m, "People disc radius (m)")->capture_default_str();
  cmd->add_option("--people-speed", o.people_speed_mps, "People walking speed (m/s)")->capture_default_str();
  cmd->add_option("--odometry-translation-sigma", o.odometry_translation_sigma,
                  "Multiplicative translation noise per increment (fraction)")
      ->capture_default_str();
  cmd->add_option("--odometry-rotation-sigma", o.odometry_rotation_sigma,
                  "Multiplicative rotation noise per increment (fraction)")
      ->capture_default_str();
  cmd->add_option("--odometry-translation-bias", o.odometry_translation_bias, "Translation scale error (fraction)")
      ->capture_default_str();
  cmd->add_option("--heading-drift", o.odometry_heading_drift_rad_per_m, "Odometry heading drift (rad/m)")
      ->capture_default_str();
  cmd->add_option("--kidnap-record", o.kidnap_record, "Teleport the robot at this record (record index; -1 = never)")
      ->capture_default_str();
  cmd->add_flag("--no-noise", cli->no_noise, "Turn every noise source off (a kidnap stays)");
  cmd->footer(ExitCodeFooter(""));
  cmd->callback([cli] {
    SimulationOptions options = cli->options;
    if (cli->no_noise) options.DisableNoise();
    std::string error;
    if (!options.IsValid(&error)) throw UsageError(error);
    std::string gt_path = cli->ground_truth;
    if (gt_path.empty()) gt_path = std::filesystem::path(cli->output).replace_extension(".gt").string();
    CheckOutputPaths({cli->output, gt_path});
    OccupancyGrid grid;
    if (cli->map_path.empty()) {
      grid = GenerateOfficeMap(OfficeMapOptions{});
    } else {
      MapLoadOptions map_options = cli->map_options;
      map_options.format = cli->map_format;
      if (!cli->map_convention.empty()) map_options.convention = ParseValueConvention(cli->map_convention);
      if (cli->map_resolution_m > 0) map_options.resolution_m = cli->map_resolution_m;
      LoadedMap loaded = LoadMap(cli->map_path, map_options);
      PrintMapLines(std::cout, cli->map_path, loaded);
      grid = std::move(loaded.grid);
    }
    SimulatedTrace sim;
    try {
      sim = SimulateTrace(grid, options);
    } catch (const NoRoomToDrive& e) {
      throw InputError(cli->map_path.empty() ? "generated office map" : cli->map_path, 0, "", e.what());
    }
    WriteCmuLog(sim.trace, cli->output);
    WriteGroundTruth(gt_path, sim.ground_truth);
    std::cout << "wrote " << cli->output << " (" << sim.trace.scans.size() << " laser records) and " << gt_path
              << (sim.kidnap_record >= 0 ? "; kidnapped at record " + std::to_string(sim.kidnap_record) : "") << "\n";
  });
}

}  // namespace rc
