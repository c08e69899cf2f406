// `rcbench backends`: every backend's cost-model parameters with value,
// unit and source, optionally after a JSON override file.
#include <iostream>

#include "backends/backend.h"
#include "backends/backend_params.h"
#include "backends/backend_preset.h"
#include "common/exit_codes.h"
#include "workloads/rcbench/commands.h"

namespace rc {

void AddBackendsCommand(CLI::App& app) {
  auto params_path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("backends", "Print every backend's cost parameters (value, unit, source)");
  cmd->add_option("--backend-params", *params_path,
                  "A named preset (artifact) or a JSON file overriding backend cost parameters, applied first (as "
                  "every pricing subcommand's --backend-params)");
  cmd->footer(ExitCodeFooter(""));
  cmd->callback([params_path] {
    const BackendParameters params =
        params_path->empty() ? BackendParameters{} : LoadBackendPreset(*params_path).backend;
    std::cout << "backends:";
    for (const auto& name : Backend::Names()) std::cout << " " << name;
    std::cout << "\n\n";
    for (const auto& name : Backend::Names()) {
      const auto backend = Backend::Create(name, params);
      std::cout << name << ": " << backend->specs().description << "\n";
    }
    std::cout << "\n";
    PrintBackendParameters(std::cout, params, *params_path);
  });
}

}  // namespace rc
