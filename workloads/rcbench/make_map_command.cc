// `rcbench make-map`: writes a generated map as ROS map_server YAML + PGM,
// for the default demo, the tests and anyone's experiments: the office
// (short rays; maps/office_map_generator.h) or the open hall (long rays;
// maps/hall_map_generator.h).
#include <filesystem>
#include <iostream>
#include <optional>

#include "common/atomic_file.h"
#include "common/exit_codes.h"
#include "common/input_error.h"
#include "maps/hall_map_generator.h"
#include "maps/office_map_generator.h"
#include "maps/ros_map_io.h"
#include "workloads/rcbench/commands.h"

namespace rc {

void AddMakeMapCommand(CLI::App& app) {
  struct Cli {
    std::string kind = "office";
    std::string output;                  // default: out/<kind>.yaml
    std::optional<double> resolution_m;  // unset: the kind's default
    std::uint64_t seed = 1;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* cmd = app.add_subcommand(
      "make-map", "Write a generated map (ROS YAML + PGM): the 20 m x 15 m office or the 60 m x 40 m open hall");
  cmd->add_option("--kind", cli->kind,
                  "office (rooms and a corridor: short rays) | hall (an open warehouse hall: rays up to 60 m)")
      ->check(CLI::IsMember({"office", "hall"}))
      ->capture_default_str();
  cmd->add_option("--output", cli->output, "YAML path; the PGM is written beside it (default: out/<kind>.yaml)");
  cmd->add_option("--resolution", cli->resolution_m,
                  "Cell size (m): office in [0.02, 0.1], default 0.05; hall in [0.05, 0.2], default 0.1");
  cmd->add_option("--seed", cli->seed, "Furniture (office) or pallet (hall) placement seed (unitless)")
      ->capture_default_str();
  cmd->footer(ExitCodeFooter(""));
  cmd->callback([cli] {
    if (cli->output.empty()) cli->output = "out/" + cli->kind + ".yaml";
    OccupancyGrid grid;
    if (cli->kind == "hall") {
      HallMapOptions options;
      options.seed = cli->seed;
      if (cli->resolution_m) options.resolution_m = *cli->resolution_m;
      grid = GenerateHallMap(options);  // throws UsageError on a bad resolution
    } else {
      OfficeMapOptions options;
      options.seed = cli->seed;
      if (cli->resolution_m) options.resolution_m = *cli->resolution_m;
      grid = GenerateOfficeMap(options);
    }
    // SaveRosMap's image goes beside the YAML under the YAML's stem.
    const std::filesystem::path yaml(cli->output);
    CheckOutputPaths({cli->output, (yaml.parent_path() / (yaml.stem().string() + ".pgm")).string()});
    SaveRosMap(grid, cli->output, RosMapSaveOptions{});
    std::cout << "wrote " << cli->output << ": " << grid.size_x() << " x " << grid.size_y() << " cells of "
              << grid.resolution_m() << " m, " << grid.CountCells(CellState::kFree) << " free, "
              << grid.CountCells(CellState::kOccupied) << " occupied\n";
  });
}

}  // namespace rc
