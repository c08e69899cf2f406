#include "maps/mrpt/mrpt_map_dispatch.h"

#include "common/file_names.h"
#include "common/input_error.h"
#include "maps/mrpt/mrpt_map_loader.h"

namespace rc {
namespace {

std::string DetectMrptFormat(const std::string& path) {
  if (FileNameEndsWith(path, ".gridmap") || FileNameEndsWith(path, ".gridmap.gz")) return "gridmap";
  if (FileNameEndsWith(path, ".simplemap") || FileNameEndsWith(path, ".simplemap.gz")) return "simplemap";
  return "";
}

void Reject(bool is_set, const std::string& option, const std::string& format) {
  if (is_set) throw UsageError("option '" + option + "' does not apply to " + format + " maps");
}

}  // namespace

LoadedMapWithOrigin LoadMapWithMrpt(const std::string& path, const MapLoadOptions& options) {
  const std::string format = options.format == "auto" ? DetectMrptFormat(path) : options.format;
  LoadedMapWithOrigin out;
  if (format != "gridmap" && format != "simplemap") {
    out.map = LoadMap(path, options);
    if (out.map.ros) {
      out.origin_x_m = out.map.ros->origin_x_m;
      out.origin_y_m = out.map.ros->origin_y_m;
    }
    return out;
  }
  Reject(options.convention.has_value(), "value convention", format + " (MRPT cells are P(free) by definition)");
  const ProbabilityThresholds thresholds = ThresholdsFrom(options);
  MrptGridMap mrpt;
  if (format == "gridmap") {
    Reject(options.resolution_m.has_value(), "resolution", "gridmap (the file declares it)");
    mrpt = LoadMrptGridmap(path, thresholds);
  } else {
    mrpt = LoadMrptSimplemap(path, options.resolution_m.value_or(kSimplemapDefaultResolution_m), thresholds);
  }
  out.map.format = format;
  out.map.cell_classes = mrpt.cell_classes;
  out.map.value_convention = DescribeMrptGridMap(mrpt);
  out.map.grid = std::move(mrpt.grid);
  out.origin_x_m = mrpt.x_min_m;
  out.origin_y_m = mrpt.y_min_m;
  return out;
}

}  // namespace rc
