#pragma once
// Map options shared by every subcommand that loads a 2D map (delibot,
// carribot, simulate), and the map line they print, so the three agree.
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "maps/map_loader.h"

namespace rc {

// Adds --occupied-thresh and --free-thresh, which fill `options` when given.
void AddMapThresholdOptions(CLI::App& command, MapLoadOptions& options);

// "map: PATH (format, X x Y cells of R m; convention)" and a second line
// with the cells of each class (cell_classes.h).
void PrintMapLines(std::ostream& out, const std::string& path, const LoadedMap& map);

}  // namespace rc
