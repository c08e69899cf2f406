#include "backends/backend_preset.h"

#include <climits>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "backends/json_document.h"
#include "common/input_error.h"

namespace rc {
namespace {

RayKernelChoices ParseKernelChoices(const nlohmann::json& kernel, const std::string& file_name) {
  if (!kernel.is_object()) throw InputError(file_name, 0, "kernel", "expected an object, got " + kernel.dump());
  RayKernelChoices choices;
  for (auto it = kernel.begin(); it != kernel.end(); ++it) {
    const std::string key = "kernel." + it.key();
    if (it.key() == "grid_cell_bytes") {
      if (!it.value().is_number_integer())
        throw InputError(file_name, 0, key, "expected an integer, got " + it.value().dump());
      const long long bytes = it.value().get<long long>();
      if (bytes < 1 || bytes > INT_MAX) throw InputError(file_name, 0, key, "must be 1, 2, 4 or 8 bytes");
      choices.grid_cell_bytes = static_cast<std::uint32_t>(bytes);
    } else if (it.key() == "march_program") {
      if (!it.value().is_string() || !ParseMarchProgramChoice(it.value().get<std::string>(), &choices.march_program))
        throw InputError(file_name, 0, key, "expected \"shipped\" or \"artifact\", got " + it.value().dump());
    } else {
      throw InputError(file_name, 0, key, "unknown kernel choice (grid_cell_bytes, march_program)");
    }
  }
  std::string error;
  if (!choices.IsValid(&error)) throw InputError(file_name, 0, "kernel.grid_cell_bytes", error);
  return choices;
}

}  // namespace

BackendPreset DefaultPreset() { return BackendPreset{"default", BackendParameters{}, RayKernelChoices{}}; }

BackendPreset ArtifactPreset() {
  BackendPreset preset = ParseBackendPreset(ArtifactPresetJson(), "backends/presets/artifact.json");
  preset.name = "artifact";
  return preset;
}

BackendPreset ParseBackendPreset(const std::string& json_text, const std::string& file_name) {
  nlohmann::json j = ParseJsonDocument(json_text, file_name);
  if (!j.is_object()) throw InputError(file_name, 0, "", "expected a JSON object at the top level");
  BackendPreset preset;
  preset.name = file_name;
  if (auto it = j.find("kernel"); it != j.end()) {
    preset.kernel = ParseKernelChoices(*it, file_name);
    j.erase(it);
  }
  preset.backend = ParseBackendParameters(j.dump(), file_name);
  return preset;
}

BackendPreset LoadBackendPreset(const std::string& name_or_path) {
  if (name_or_path == "default") return DefaultPreset();
  if (name_or_path == "artifact") return ArtifactPreset();
  const std::string& path = name_or_path;
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open the backend preset file");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseBackendPreset(text.str(), path);
}

}  // namespace rc
