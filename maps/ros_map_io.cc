#include "maps/ros_map_io.h"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/text_fields.h"

namespace rc {
namespace {

// map_saver's grey levels and the thresholds it writes beside them.
constexpr std::uint8_t kSavedOccupied = 0;
constexpr std::uint8_t kSavedFree = 254;
constexpr std::uint8_t kSavedUnknown = 205;
constexpr double kSavedOccupiedThresh = 0.65;
constexpr double kSavedFreeThresh = 0.196;

const char* const kKnownKeys[] = {"image", "resolution", "origin", "occupied_thresh", "free_thresh", "negate", "mode"};

// The top-level keys of a map YAML, with every error located at a line.
class MapYaml {
 public:
  MapYaml(std::string file, const YAML::Node& root) : file_(std::move(file)) {
    if (!root.IsMap()) Fail(root, "", "expected a mapping of map_server keys (image, resolution, origin, ...)");
    for (const auto& entry : root) {
      // Copies: yaml-cpp's iterator yields a temporary pair of handles.
      const YAML::Node key = entry.first;
      if (!key.IsScalar()) Fail(key, "", "a key must be a plain name");
      const std::string name = key.Scalar();
      bool known = false;
      for (const char* k : kKnownKeys) known = known || name == k;
      if (!known)
        Fail(key, name,
             "unknown key (expected image, resolution, origin, occupied_thresh, "
             "free_thresh, negate, mode)");
      if (values_.count(name)) Fail(key, name, "appears twice");
      values_[name] = entry.second;
      key_lines_[name] = LineOf(key);
    }
  }

  bool Has(const std::string& key) const { return values_.count(key) > 0; }

  const YAML::Node& Get(const std::string& key) const {
    auto it = values_.find(key);
    if (it == values_.end()) throw InputError(file_, 0, key, "missing required key");
    if (it->second.IsNull()) FailKey(key, "has no value");
    return it->second;
  }

  std::string String(const std::string& key) const {
    const YAML::Node& node = Get(key);
    if (!node.IsScalar()) FailKey(key, "expected a single value");
    return node.Scalar();
  }

  double Number(const YAML::Node& node, const std::string& field) const {
    if (!node.IsScalar()) Fail(node, field, "expected a number");
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      Fail(node, field, "'" + node.Scalar() + "' is not a number");
    }
    if (!std::isfinite(value)) Fail(node, field, "'" + node.Scalar() + "' is not finite (NaN or inf)");
    return value;
  }
  double Number(const std::string& key) const { return Number(Get(key), key); }

  bool Flag(const std::string& key) const {
    const YAML::Node& node = Get(key);
    if (!node.IsScalar()) FailKey(key, "expected 0, 1, false or true");
    try {
      const int value = node.as<int>();
      if (value == 0 || value == 1) return value == 1;
    } catch (const YAML::Exception&) {
      try {
        return node.as<bool>();
      } catch (const YAML::Exception&) {
      }
    }
    FailKey(key, "'" + node.Scalar() + "' is not 0, 1, false or true");
  }

  // The line of the key itself: where a reader looks, and the only place a
  // null value has (yaml-cpp marks it at the next token).
  long LineOf(const std::string& key) const {
    auto it = key_lines_.find(key);
    return it == key_lines_.end() ? 0 : it->second;
  }
  static long LineOf(const YAML::Node& node) {
    const YAML::Mark mark = node.Mark();
    return mark.is_null() ? 0 : mark.line + 1;  // yaml-cpp counts lines from 0
  }

  [[noreturn]] void Fail(const YAML::Node& node, const std::string& field, const std::string& problem) const {
    throw InputError(file_, LineOf(node), field, problem);
  }
  [[noreturn]] void FailKey(const std::string& key, const std::string& problem) const {
    throw InputError(file_, LineOf(key), key, problem);
  }

 private:
  std::string file_;
  std::map<std::string, YAML::Node> values_;
  std::map<std::string, long> key_lines_;
};

ImageMapMode ParseMode(const MapYaml& yaml) {
  if (!yaml.Has("mode")) return ImageMapMode::kTrinary;  // map_server's default
  const std::string mode = yaml.String("mode");
  for (ImageMapMode m : {ImageMapMode::kTrinary, ImageMapMode::kScale, ImageMapMode::kRaw})
    if (mode == ToString(m)) return m;
  yaml.FailKey("mode", "'" + mode + "' is not trinary, scale or raw");
}

void ParseOrigin(const MapYaml& yaml, RosMapMetadata* meta) {
  const YAML::Node& origin = yaml.Get("origin");
  if (!origin.IsSequence() || origin.size() != 3) yaml.FailKey("origin", "expected [x, y, yaw] (three numbers)");
  meta->origin_x_m = yaml.Number(origin[0], "origin[0]");
  meta->origin_y_m = yaml.Number(origin[1], "origin[1]");
  meta->origin_yaw_rad = yaml.Number(origin[2], "origin[2]");
}

std::string ResolveImagePath(const std::string& yaml_path, const std::string& image) {
  const std::filesystem::path image_path(image);
  if (image_path.is_absolute()) return image;
  return (std::filesystem::path(yaml_path).parent_path() / image_path).string();
}

std::string FormatNumber(double value) {
  // Shortest text that reads back to the same double.
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

bool IsPlainFileName(const std::string& name) {
  if (name.empty() || name == "." || name == "..") return false;
  for (char c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') return false;
  return true;
}

std::uint8_t SavedGrey(CellState s) {
  switch (s) {
    case CellState::kOccupied: return kSavedOccupied;
    case CellState::kFree: return kSavedFree;
    case CellState::kUnknown: return kSavedUnknown;
  }
  return kSavedUnknown;
}

}  // namespace

RosMap LoadRosMap(const std::string& yaml_path) {
  // yaml-cpp would open a directory and fail on its first read with a
  // std::ios_base::failure that names no file.
  RejectDirectory(yaml_path);
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml_path);
  } catch (const YAML::BadFile&) {
    throw InputError(yaml_path, 0, "", "cannot open map YAML file");
  } catch (const YAML::ParserException& e) {
    throw InputError(yaml_path, e.mark.is_null() ? 0 : e.mark.line + 1, "", "YAML syntax error: " + e.msg);
  }
  const MapYaml yaml(yaml_path, root);

  RosMapMetadata meta;
  meta.yaml_path = yaml_path;
  const std::string image = yaml.String("image");
  if (image.empty()) yaml.FailKey("image", "is empty");
  meta.image_path = ResolveImagePath(yaml_path, image);
  meta.resolution_m = yaml.Number("resolution");
  if (!(meta.resolution_m > 0.0))
    yaml.FailKey("resolution", "must be positive (m per cell), got " + yaml.Get("resolution").Scalar());
  ParseOrigin(yaml, &meta);
  meta.thresholds.occupied_thresh = yaml.Number("occupied_thresh");
  meta.thresholds.free_thresh = yaml.Number("free_thresh");
  meta.thresholds.negate = yaml.Flag("negate");
  meta.mode = ParseMode(yaml);

  std::string field, problem;
  if (!CheckPixelThresholds(meta.thresholds, &field, &problem))
    throw InputError(yaml_path, yaml.LineOf(field), field, problem);
  if (meta.mode == ImageMapMode::kRaw && meta.thresholds.negate)
    throw InputError(yaml_path, yaml.LineOf("negate"), "negate",
                     "negate has no agreed meaning in raw mode (ROS 1 applies it, Nav2 ignores "
                     "it); write the image un-negated and set negate: 0");
  if (!std::ifstream(meta.image_path))
    throw InputError(yaml_path, yaml.LineOf("image"), "image",
                     "image file '" + meta.image_path + "' does not exist or cannot be opened");

  RosMap map;
  try {
    map.grid = ReadImageGrid(meta.image_path, meta.resolution_m, meta.thresholds, meta.mode, &map.cell_classes);
  } catch (const InputError& e) {
    // The image's own error (its file, line and field) behind the YAML key
    // that named it: the user ran the YAML and may not know the image.
    yaml.FailKey("image", e.what());
  }
  map.metadata = std::move(meta);
  return map;
}

void SaveRosMap(const OccupancyGrid& grid, const std::string& yaml_path, const RosMapSaveOptions& options) {
  if (!std::isfinite(options.origin_x_m) || !std::isfinite(options.origin_y_m) ||
      !std::isfinite(options.origin_yaw_rad))
    throw std::invalid_argument("SaveRosMap: the origin must be finite");
  const std::filesystem::path yaml(yaml_path);
  const std::string image_name =
      options.image_file_name.empty() ? yaml.stem().string() + ".pgm" : options.image_file_name;
  if (!IsPlainFileName(image_name))
    throw std::invalid_argument("SaveRosMap: image file name '" + image_name +
                                "' must be a plain name of letters, digits, '.', '_' or '-'");

  // Binary PGM (P5), top row first: row r holds iy = size_y - 1 - r.
  AtomicFile image((yaml.parent_path() / image_name).string());
  image.stream() << "P5\n# CREATOR: rcbench SaveRosMap " << FormatNumber(grid.resolution_m()) << " m/pix\n"
                 << grid.size_x() << ' ' << grid.size_y() << "\n255\n";
  std::string row(static_cast<std::size_t>(grid.size_x()), '\0');
  for (int iy = grid.size_y() - 1; iy >= 0; --iy) {
    for (int ix = 0; ix < grid.size_x(); ++ix) row[ix] = static_cast<char>(SavedGrey(grid.At(ix, iy)));
    image.stream().write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  image.Commit();

  AtomicFile out(yaml_path);
  out.stream() << "image: " << image_name << "\n"
               << "mode: trinary\n"
               << "resolution: " << FormatNumber(grid.resolution_m()) << "\n"
               << "origin: [" << FormatNumber(options.origin_x_m) << ", " << FormatNumber(options.origin_y_m) << ", "
               << FormatNumber(options.origin_yaw_rad) << "]\n"
               << "negate: 0\n"
               << "occupied_thresh: " << FormatNumber(kSavedOccupiedThresh) << "\n"
               << "free_thresh: " << FormatNumber(kSavedFreeThresh) << "\n";
  out.Commit();
}

}  // namespace rc
