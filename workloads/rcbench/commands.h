#pragma once
// Each rcbench subcommand lives in its own file and registers itself here.
#include <CLI/CLI.hpp>

namespace rc {

void AddDelibotCommand(CLI::App& app);
void AddCarribotCommand(CLI::App& app);
void AddSimulateCommand(CLI::App& app);
void AddMakeMapCommand(CLI::App& app);
void AddBackendsCommand(CLI::App& app);
void AddCollideCommand(CLI::App& app);
void AddCalibrateCommand(CLI::App& app);
void AddMovebotCommand(CLI::App& app);

}  // namespace rc
