#pragma once
// A backend preset: a whole set of choices a calibration column is priced
// under. Today's backend-parameter override format (backends/
// backend_params.h: `rcbench backends` lists every key) plus the
// kernel-side choices that are not backend parameters, under "kernel":
//   {"gpu": {...}, "simt": {...}, ...,
//    "kernel": {"grid_cell_bytes": 8, "march_program": "artifact"}}
// (robocore/ray_batch_recorded.h, RayKernelChoices: how the device stores
// the DeliBot grid and which march program the RT units run).
//
// The artifact preset (backends/presets/artifact.json, embedded at build
// time) is the RoboGPU artifact's own configuration and code, cited line
// by line in docs/artifact_preset.md; never fitted to the paper's ratios.
#include <string>

#include "backends/backend_params.h"
#include "robocore/ray_batch_recorded.h"

namespace rc {

struct BackendPreset {
  std::string name;  // "default", "artifact", or the file it came from
  BackendParameters backend;
  RayKernelChoices kernel;
};

// Our defaults: BackendParameters{} and RayKernelChoices{}.
BackendPreset DefaultPreset();
// backends/presets/artifact.json as embedded in the binary.
BackendPreset ArtifactPreset();
// The embedded text of backends/presets/artifact.json.
const char* ArtifactPresetJson();

// Parses a preset: "kernel" (optional; keys grid_cell_bytes, an integer 1,
// 2, 4 or 8, and march_program, "shipped" or "artifact") is taken out and
// the rest goes to ParseBackendParameters. Throws InputError naming
// `file_name` and the key for bad JSON, an unknown key, a wrong type or an
// invalid value.
BackendPreset ParseBackendPreset(const std::string& json_text, const std::string& file_name);
// `--backend-params NAME|FILE`: a named preset ("default", "artifact") or a
// preset file read by ParseBackendPreset (a file that happens to be called
// "artifact" is read as ./artifact). The file goes through the same checks
// as any backend-parameter file: every parameter within its declared range.
BackendPreset LoadBackendPreset(const std::string& name_or_path);

}  // namespace rc
