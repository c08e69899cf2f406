#include "maps/map_loader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/input_error.h"
#include "common/text_fields.h"
#include "maps/cmu_map_loader.h"
#include "maps/image_map_loader.h"
#include "maps/movingai_map_loader.h"
#include "maps/rowild_map_loader.h"

namespace rc {
namespace {

std::string LowercaseExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Both probability formats use .dat; their first header line tells them apart.
std::string DetectDatFormat(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open map file");
  LineReader reader(in, path);
  std::string line;
  while (reader.Next(line)) {
    const auto fields = SplitFields(line);
    if (fields.empty()) continue;
    if (fields[0].rfind("robot_specifications->", 0) == 0) return "cmu";
    if (fields[0] == "mapsize_x") return "rowild";
    reader.Fail("header",
                "a .dat map must start with 'robot_specifications->' (CMU) or "
                "'mapsize_x' (RoWild); name the format explicitly to override");
  }
  throw InputError(path, 0, "header", "the file is empty");
}

std::string DetectFormat(const std::string& path) {
  const std::string ext = LowercaseExtension(path);
  if (ext == ".dat") return DetectDatFormat(path);
  if (ext == ".yaml" || ext == ".yml") return "ros";
  if (ext == ".map") return "movingai";
  if (ext == ".png" || ext == ".pgm" || ext == ".jpg" || ext == ".jpeg") return "image";
  throw InputError(path, 0, "extension",
                   "unknown map extension '" + ext +
                       "' (expected .dat, .yaml, .yml, .map, .png, .pgm, .jpg, .jpeg); name the "
                       "format explicitly to override");
}

void RejectOption(bool is_set, const std::string& option, const std::string& format) {
  if (is_set) throw UsageError("option '" + option + "' does not apply to " + format + " maps");
}

std::string Number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string DescribeProbability(ValueConvention c, const ProbabilityThresholds& t) {
  const std::string meaning = c == ValueConvention::kProbabilityFree
                                  ? "values are P(free) (the Wean data's real convention), P(occupied) = 1 - value"
                                  : "values are P(occupied) (the format note's and RoWild's reading, which inverts the "
                                    "Wean data)";
  return meaning + "; occupied if P(occupied) >= " + Number(t.occupied_thresh) +
         ", free if <= " + Number(t.free_thresh) + ", unknown between and for -1";
}

std::string DescribePixels(const PixelThresholds& t, ImageMapMode mode) {
  std::string text = "map_server " + ToString(mode) +
                     " rule: p = " + (t.negate ? "v / 255 (negate)" : "(255 - v) / 255") +
                     " for channel mean v; occupied if p > " + Number(t.occupied_thresh) + ", free if p < " +
                     Number(t.free_thresh) + ", else unknown";
  if (mode == ImageMapMode::kScale) text += " (scale mode's partial values become unknown)";
  if (mode == ImageMapMode::kRaw)
    text = "map_server raw values: v = occupancy percent, occupied if v/100 > " + Number(t.occupied_thresh) +
           ", free if v/100 < " + Number(t.free_thresh) + ", 255 unknown";
  return text;
}

}  // namespace

ProbabilityThresholds ThresholdsFrom(const MapLoadOptions& options) {
  ProbabilityThresholds t;
  if (options.occupied_thresh) t.occupied_thresh = *options.occupied_thresh;
  if (options.free_thresh) t.free_thresh = *options.free_thresh;
  CheckProbabilityThresholds(t);
  return t;
}

LoadedMap LoadMap(const std::string& path, const MapLoadOptions& options) {
  const std::string format = options.format == "auto" ? DetectFormat(path) : options.format;
  const bool thresholds_set = options.occupied_thresh.has_value() || options.free_thresh.has_value();
  LoadedMap out;
  out.format = format;
  if (format == "cmu" || format == "rowild") {
    RejectOption(options.resolution_m.has_value(), "resolution", format + " (the file declares it)");
    const ValueConvention convention = options.convention.value_or(ValueConvention::kProbabilityFree);
    const ProbabilityThresholds thresholds = ThresholdsFrom(options);
    if (format == "cmu") {
      CmuMapOptions o;
      o.convention = convention;
      o.thresholds = thresholds;
      out.grid = LoadCmuMap(path, o, &out.cell_classes);
    } else {
      RowildMapOptions o;
      o.convention = convention;
      o.thresholds = thresholds;
      out.grid = LoadRowildMap(path, o, &out.cell_classes);
    }
    out.value_convention = DescribeProbability(convention, thresholds);
  } else if (format == "ros") {
    RejectOption(options.convention.has_value(), "value convention", "ros");
    RejectOption(options.resolution_m.has_value(), "resolution", "ros (the YAML declares it)");
    RejectOption(thresholds_set, "occupied/free thresholds",
                 "ros (the YAML declares occupied_thresh and free_thresh; edit them there)");
    RosMap ros = LoadRosMap(path);
    out.grid = std::move(ros.grid);
    out.cell_classes = ros.cell_classes;
    out.value_convention = DescribePixels(ros.metadata.thresholds, ros.metadata.mode);
    out.ros = std::move(ros.metadata);
  } else if (format == "movingai") {
    RejectOption(options.convention.has_value(), "value convention", "movingai");
    RejectOption(thresholds_set, "occupied/free thresholds", "movingai (cells are terrain letters)");
    MovingAiMapOptions o;
    o.resolution_m = options.resolution_m.value_or(o.resolution_m);
    out.grid = LoadMovingAiMap(path, o);
    out.cell_classes = CountStates(out.grid);
    out.value_convention =
        "MovingAI terrain: '.' 'G' free; '@' 'O' 'T' 'S' 'W' occupied; " + Number(o.resolution_m) + " m per cell";
  } else if (format == "image") {
    RejectOption(options.convention.has_value(), "value convention", "image");
    if (!options.resolution_m) throw UsageError("an image map needs a resolution (m per cell); the image has no scale");
    ImageMapOptions o;
    o.resolution_m = *options.resolution_m;
    const ProbabilityThresholds thresholds = ThresholdsFrom(options);
    o.thresholds.occupied_thresh = thresholds.occupied_thresh;
    o.thresholds.free_thresh = thresholds.free_thresh;
    out.grid = LoadImageMap(path, o, &out.cell_classes);
    out.value_convention =
        DescribePixels(o.thresholds, ImageMapMode::kTrinary) + ", " + Number(o.resolution_m) + " m per cell";
  } else {
    throw UsageError("unknown map format '" + format + "' (expected auto, cmu, rowild, ros, movingai or image)");
  }
  return out;
}

}  // namespace rc
