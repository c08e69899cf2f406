#include "traces/ground_truth_io.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/text_fields.h"
#include "traces/record_fields.h"

namespace rc {
namespace {

const char* const kColumns = "t_s x_m y_m theta_rad";
constexpr double kTimeTolerance_s = 1e-6;

}  // namespace

GroundTruth ReadGroundTruth(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open ground-truth file");
  LineReader reader(in, path);
  GroundTruth truth;
  truth.source_path = path;
  std::string line;
  while (reader.Next(line)) {
    const auto f = SplitFields(line);
    if (f.empty() || f[0][0] == '#') continue;
    static const char* const kNames[] = {"t", "x", "y", "theta"};
    RequireFieldCount(
        reader, f.size(), 4, [](std::size_t i) { return std::string(kNames[i]); }, kColumns);
    GroundTruthPose p;
    p.time_s = reader.ParseDouble(f[0], "t");
    p.pose.x = reader.ParseDouble(f[1], "x");
    p.pose.y = reader.ParseDouble(f[2], "y");
    p.pose.theta = reader.ParseDouble(f[3], "theta");
    p.source_line = reader.line_number();
    truth.poses.push_back(p);
  }
  if (truth.poses.empty()) throw InputError(path, 0, "poses", "the ground-truth file has no poses");
  return truth;
}

void WriteGroundTruth(const std::string& path, const std::vector<GroundTruthPose>& poses) {
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "# " << kColumns << "\n";
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const GroundTruthPose& p = poses[k];
    if (!std::isfinite(p.time_s) || !std::isfinite(p.pose.x) || !std::isfinite(p.pose.y) ||
        !std::isfinite(p.pose.theta))
      throw std::invalid_argument("ground-truth pose " + std::to_string(k) + " for '" + path + "' is not finite");
    out << fmt::format("{:.17g} {:.17g} {:.17g} {:.17g}\n", p.time_s, p.pose.x, p.pose.y, p.pose.theta);
  }
  file.Commit();
}

void CheckGroundTruthMatches(ScanSource& scans, const GroundTruth& truth) {
  if (truth.poses.size() != scans.size())
    throw InputError(truth.source_path, 0, "poses",
                     std::to_string(truth.poses.size()) + " ground-truth poses for " + std::to_string(scans.size()) +
                         " laser records in '" + scans.source_path() + "'; the files pair line by line");
  scans.Rewind();
  LaserScan scan;
  for (std::size_t k = 0; k < truth.poses.size() && scans.Next(scan); ++k) {
    const double t_truth = truth.poses[k].time_s;
    if (std::abs(t_truth - scan.time_s) > kTimeTolerance_s) {
      const std::string text = fmt::format("pose {} has time {:.6f} s, but laser record {} has {:.6f} s ('{}' line {})",
                                           k + 1, t_truth, k + 1, scan.time_s, scans.source_path(), scan.source_line);
      throw InputError(truth.source_path, truth.poses[k].source_line, "t", text);
    }
  }
  scans.Rewind();
}

void CheckGroundTruthMatches(const SensorTrace& trace, const GroundTruth& truth) {
  InMemoryScanSource scans(trace);
  CheckGroundTruthMatches(scans, truth);
}

}  // namespace rc
