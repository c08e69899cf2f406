#include "workloads/rcbench/map_options.h"

namespace rc {

void AddMapThresholdOptions(CLI::App& command, MapLoadOptions& options) {
  command.add_option_function<double>(
      "--occupied-thresh", [&options](double v) { options.occupied_thresh = v; },
      "A cell is occupied when its P(occupied) reaches this (probability; default 0.65, ROS map_server's). For "
      "probability maps (.dat), images and MRPT grids; a ROS YAML declares its own");
  command.add_option_function<double>(
      "--free-thresh", [&options](double v) { options.free_thresh = v; },
      "A cell is free when its P(occupied) is at most this (probability; default 0.196, ROS map_server's); cells "
      "between the two thresholds are unknown");
}

void PrintMapLines(std::ostream& out, const std::string& path, const LoadedMap& map) {
  out << "map: " << path << " (" << map.format << ", " << map.grid.size_x() << " x " << map.grid.size_y()
      << " cells of " << map.grid.resolution_m() << " m; " << map.value_convention << ")\n"
      << "map cells: " << map.cell_classes.Describe() << "\n";
}

}  // namespace rc
