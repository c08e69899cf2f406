// rcbench: robotics kernels on modelled GPU backends.
//
// Exit codes: 0 success; 1 bad input (a file, a value, or a run that cannot
// proceed, e.g. a map with no free cell), with one message naming the file,
// line and field; 2 bad command-line usage; 3 `carribot` found no path for
// at least one query, or `movebot` found no exact path (after writing all
// their outputs).
#include <cstdio>
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "common/input_error.h"
#include "workloads/rcbench/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"rcbench: robotics kernels (MCL ray casting, A*, RRT*) on modelled GPU backends"};
  app.require_subcommand(1);
  rc::AddDelibotCommand(app);
  rc::AddCarribotCommand(app);
  rc::AddSimulateCommand(app);
  rc::AddMakeMapCommand(app);
  rc::AddBackendsCommand(app);
  rc::AddCollideCommand(app);
  rc::AddCalibrateCommand(app);
  rc::AddMovebotCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  } catch (const rc::UsageError& e) {
    std::cerr << "rcbench: usage: " << e.what() << "\n";
    return 2;
  } catch (const rc::InputError& e) {
    std::cerr << "rcbench: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "rcbench: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
