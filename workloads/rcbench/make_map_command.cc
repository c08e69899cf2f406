// `rcbench make-map`: writes the generated office-like map as ROS map_server
// YAML + PGM, for the default demo, the tests and anyone's experiments.
#include <filesystem>
#include <iostream>

#include "common/input_error.h"
#include "maps/office_map_generator.h"
#include "maps/ros_map_io.h"
#include "workloads/rcbench/commands.h"

namespace rc {

void AddMakeMapCommand(CLI::App& app) {
  struct Cli {
    std::string output = "out/office.yaml";
    OfficeMapOptions options;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* cmd = app.add_subcommand("make-map", "Write the generated 20 m x 15 m office map (ROS YAML + PGM)");
  cmd->add_option("--output", cli->output, "YAML path; the PGM is written beside it")->capture_default_str();
  cmd->add_option("--resolution", cli->options.resolution_m, "Cell size (m), in [0.02, 0.1]")->capture_default_str();
  cmd->add_option("--seed", cli->options.seed, "Furniture placement seed (unitless)")->capture_default_str();
  cmd->callback([cli] {
    std::string error;
    if (!cli->options.IsValid(&error)) throw UsageError(error);
    const OccupancyGrid grid = GenerateOfficeMap(cli->options);
    const auto parent = std::filesystem::path(cli->output).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    SaveRosMap(grid, cli->output, RosMapSaveOptions{});
    std::cout << "wrote " << cli->output << ": " << grid.size_x() << " x " << grid.size_y() << " cells of "
              << grid.resolution_m() << " m, " << grid.CountCells(CellState::kFree) << " free, "
              << grid.CountCells(CellState::kOccupied) << " occupied\n";
  });
}

}  // namespace rc
