#include "traces/mrpt/mrpt_rawlog_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/serialization/CArchive.h>

#include "common/allocation_budget.h"
#include "common/input_error.h"
#include "common/memory_cap.h"
#include "traces/mrpt/mrpt_archive_bytes.h"

namespace rc {
namespace {

// Same tolerances as the CMU and CARMEN readers' mount check (laser_mount.h).
constexpr double kMountPositionTolerance_m = 0.005;
constexpr double kMountAngleTolerance_rad = 1e-3;
// Two scans of one laser agree on their geometry to float precision.
constexpr double kGeometryTolerance = 1e-6;

std::string Entry(std::size_t index) { return "entry " + std::to_string(index); }

class RawlogParser {
 public:
  RawlogParser(std::string path, RawlogReadOptions options, TraceReadStats& stats)
      : path_(std::move(path)), options_(std::move(options)), stats_(stats) {
    trace_.source_path = path_;
    trace_.format = "rawlog";
  }

  void Handle(const mrpt::serialization::CSerializable::Ptr& object, std::size_t entry) {
    entry_ = entry;
    if (auto actions = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(object)) {
      SetForm(Form::kActionsObservations, "a CActionCollection");
      HandleActions(*actions);
    } else if (auto frame = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(object)) {
      SetForm(Form::kActionsObservations, "a CSensoryFrame");
      bool took_scan = false;
      for (const auto& observation : *frame) {
        if (took_scan) {
          ++stats_.skipped_records;  // a second scan in one frame would share the pose
          continue;
        }
        took_scan = HandleObservation(observation);
      }
    } else if (auto observation = std::dynamic_pointer_cast<mrpt::obs::CObservation>(object)) {
      SetForm(Form::kObservationsOnly, "a bare " + std::string(object->GetRuntimeClass()->className));
      if (auto odometry = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(observation)) {
        odometry_ = Pose2{odometry->odometry.x(), odometry->odometry.y(), odometry->odometry.phi()};
        ++stats_.odometry_records;
        return;
      }
      HandleObservation(observation);
    } else {
      Fail("object", "unexpected " + std::string(object->GetRuntimeClass()->className) +
                         " (a rawlog holds actions, sensory frames or observations)");
    }
  }

  SensorTrace Finish() {
    if (trace_.scans.empty())
      throw InputError(path_, 0, "scans",
                       "no CObservation2DRangeScan" + (label_ ? " labelled '" + *label_ + "'" : std::string()) +
                           (form_ == Form::kObservationsOnly ? " after a CObservationOdometry" : "") +
                           " in the rawlog: nothing to localize with");
    return std::move(trace_);
  }

  [[noreturn]] void Fail(const std::string& field, const std::string& problem) const {
    throw InputError(path_, 0, Entry(entry_) + " " + field, problem);
  }

 private:
  enum class Form { kUnknown, kActionsObservations, kObservationsOnly };

  void SetForm(Form form, const std::string& what) {
    if (form_ == Form::kUnknown) {
      form_ = form;
      if (form == Form::kActionsObservations) odometry_ = Pose2{};
      return;
    }
    if (form_ != form)
      Fail("object", "found " + what + " in a rawlog that began in the " +
                         (form_ == Form::kObservationsOnly ? "observations-only" : "actions/observations") +
                         " form; the two forms cannot be mixed");
  }

  void HandleActions(const mrpt::obs::CActionCollection& actions) {
    const auto movement = actions.getBestMovementEstimation();
    if (!movement) Fail("action", "the CActionCollection has no CActionRobotMovement2D (odometry is required)");
    // rawOdometryIncrementReading is the odometer's own increment; other
    // estimation methods (scan matching) only fill the pose PDF.
    if (movement->estimationMethod != mrpt::obs::CActionRobotMovement2D::emOdometry && !movement->poseChange)
      Fail("action", "the CActionRobotMovement2D has no pose PDF");
    const mrpt::poses::CPose2D increment = movement->estimationMethod == mrpt::obs::CActionRobotMovement2D::emOdometry
                                               ? movement->rawOdometryIncrementReading
                                               : movement->poseChange->getMeanVal();
    if (!std::isfinite(increment.x()) || !std::isfinite(increment.y()) || !std::isfinite(increment.phi()))
      Fail("odometry increment", "not finite");
    const mrpt::poses::CPose2D composed =
        mrpt::poses::CPose2D(odometry_->x, odometry_->y, odometry_->theta) + increment;
    odometry_ = Pose2{composed.x(), composed.y(), WrapAngle(composed.phi())};
    ++stats_.odometry_records;
  }

  // Returns true when the observation became a scan of the trace.
  bool HandleObservation(const mrpt::obs::CObservation::Ptr& observation) {
    auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(observation);
    if (!scan) {
      ++stats_.skipped_records;
      return false;
    }
    if (!label_) label_ = options_.sensor_label.empty() ? scan->sensorLabel : options_.sensor_label;
    if (scan->sensorLabel != *label_ || !odometry_) {
      ++stats_.skipped_records;
      return false;
    }
    const LaserGeometry geometry = GeometryOf(*scan);
    if (trace_.scans.empty()) {
      trace_.geometry = geometry;
    } else {
      CheckSameGeometry(geometry);
    }
    LaserScan out;
    const double epoch_s = mrpt::Clock::toDouble(scan->timestamp);
    if (trace_.scans.empty()) first_epoch_s_ = epoch_s;
    out.time_s = epoch_s - first_epoch_s_;
    if (!trace_.scans.empty() && out.time_s < trace_.scans.back().time_s)
      Fail("timestamp", "scan time goes backwards (" + std::to_string(out.time_s) + " s after " +
                            std::to_string(trace_.scans.back().time_s) + " s)");
    out.odometry = *odometry_;
    out.source_line = static_cast<long>(entry_);
    const std::size_t n = scan->getScanSize();
    const bool right_to_left = BoolField(scan->rightToLeft, "rightToLeft");
    out.ranges_m.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      // LaserGeometry's beams run right to left; MRPT may store them the other way.
      const std::size_t source = right_to_left ? i : n - 1 - i;
      const float r = scan->getScanRange(source);
      if (!std::isfinite(r) || r < 0.0f)
        Fail("range " + std::to_string(source), "range " + std::to_string(r) + " m is not a distance");
      const bool valid = scan->getScanRangeValidity(source) && r < scan->maxRange;
      out.ranges_m[i] = valid ? r : static_cast<float>(geometry.max_range_m);
    }
    trace_.scans.push_back(std::move(out));
    ++stats_.laser_records;
    return true;
  }

  // MRPT reads a bool field as the file's byte: anything but 0 or 1 is no
  // bool value, and reading the field would be undefined (a tests/fuzz
  // finding under UBSan), so its byte is inspected instead.
  bool BoolField(const bool& field, const std::string& name) const {
    unsigned char byte = 0;
    std::memcpy(&byte, &field, 1);
    if (byte > 1) Fail(name, "byte " + std::to_string(byte) + " is not a bool (0 or 1)");
    return byte == 1;
  }

  LaserGeometry GeometryOf(const mrpt::obs::CObservation2DRangeScan& scan) const {
    const std::size_t n = scan.getScanSize();
    if (n < 2) Fail("scan size", std::to_string(n) + " ranges; a scan needs at least 2");
    if (!(scan.aperture > 0.0f) || scan.aperture > 2.0 * kPi + 1e-6)
      Fail("aperture", std::to_string(scan.aperture) + " rad is not in (0, 2 pi]");
    if (!(scan.maxRange > 0.0f) || !std::isfinite(scan.maxRange))
      Fail("maxRange", std::to_string(scan.maxRange) + " m is not a positive distance");
    const mrpt::poses::CPose3D& mount = scan.sensorPose;
    // Checked first: a NaN passes every tolerance comparison below.
    for (const double v : {mount.x(), mount.y(), mount.z(), mount.yaw(), mount.pitch(), mount.roll()})
      if (!std::isfinite(v)) Fail("sensorPose", "the laser's pose on the robot is not finite");
    if (std::abs(mount.y()) > kMountPositionTolerance_m)
      Fail("sensorPose", "the laser is " + std::to_string(mount.y()) +
                             " m off the robot's heading axis; LaserGeometry models only a forward offset");
    if (std::abs(mount.pitch()) > kMountAngleTolerance_rad || std::abs(mount.roll()) > kMountAngleTolerance_rad)
      Fail("sensorPose", "the laser is pitched or rolled; only a planar (yaw-only) mount is supported");
    LaserGeometry g;
    g.beam_count = static_cast<int>(n);
    g.angle_increment_rad = scan.aperture / static_cast<double>(n - 1);
    // A yaw offset rotates every beam by the same angle about the sensor,
    // which sits on the heading axis: exactly a shift of the first angle.
    g.angle_min_rad = WrapAngle(-0.5 * scan.aperture + mount.yaw());
    g.max_range_m = scan.maxRange;
    g.offset_forward_m = mount.x();
    return g;
  }

  void CheckSameGeometry(const LaserGeometry& g) const {
    const LaserGeometry& first = trace_.geometry;
    auto differs = [](double a, double b) { return std::abs(a - b) > kGeometryTolerance * std::max(1.0, std::abs(a)); };
    if (g.beam_count != first.beam_count)
      Fail("scan size",
           std::to_string(g.beam_count) + " ranges, but the first scan had " + std::to_string(first.beam_count));
    if (differs(g.angle_increment_rad, first.angle_increment_rad) || differs(g.angle_min_rad, first.angle_min_rad))
      Fail("aperture", "the scan's aperture or mount yaw differs from the first scan's");
    if (differs(g.max_range_m, first.max_range_m))
      Fail("maxRange",
           std::to_string(g.max_range_m) + " m, but the first scan had " + std::to_string(first.max_range_m) + " m");
    if (differs(g.offset_forward_m, first.offset_forward_m))
      Fail("sensorPose", "the laser mount differs from the first scan's");
  }

  std::string path_;
  RawlogReadOptions options_;
  TraceReadStats& stats_;
  SensorTrace trace_;
  Form form_ = Form::kUnknown;
  std::optional<Pose2> odometry_;  // unset until the observations-only form sees odometry
  std::optional<std::string> label_;
  std::size_t entry_ = 0;
  double first_epoch_s_ = 0.0;
};

}  // namespace

SensorTrace ReadMrptRawlog(const std::string& path, const RawlogReadOptions& options, TraceReadStats* stats) {
  TraceReadStats local_stats;
  TraceReadStats& s = stats ? *stats : local_stats;
  s = TraceReadStats{};
  const std::vector<unsigned char> bytes = ReadArchiveBytes(path, "rawlog");
  CheckMrptCrashFields(bytes, path, "rawlog");
  mrpt::io::CMemoryStream memory;
  memory.assignMemoryNotOwn(bytes.data(), bytes.size());
  auto archive = mrpt::serialization::archiveFrom(memory);
  RawlogParser parser(path, options, s);
  std::size_t entry = 0;
  // MRPT sizes each object's buffers from the counts it declares.
  const std::uint64_t budget = ParseBudgetBytes(bytes.size());
  // Read object by object: MRPT's CRawlog helpers report a corrupt archive
  // as a silent end of file, which would turn a truncated log into a
  // shorter valid one. Here the only clean end is the last byte.
  while (memory.getPosition() < bytes.size()) {
    const std::uint64_t offset = memory.getPosition();
    mrpt::serialization::CSerializable::Ptr object;
    try {
      ParseWithinBudget(budget, [&] { object = archive.ReadObject(); });
    } catch (const std::exception& e) {
      const bool over = dynamic_cast<const AllocationBudgetExceeded*>(&e) != nullptr;
      throw InputError(
          path, 0, Entry(entry),
          "corrupt or truncated rawlog at byte " + std::to_string(offset) + " of " + std::to_string(bytes.size()) +
              " (uncompressed): " +
              (over ? "its objects declare sizes that would take more than " + DescribeBytes(budget) + " of memory"
                    : MrptMessage(e.what())));
    }
    if (!object) parser.Fail("object", "a null object in the archive");
    parser.Handle(object, entry);
    ++entry;
  }
  if (entry == 0) throw InputError(path, 0, "", "the rawlog is empty");
  return parser.Finish();
}

}  // namespace rc
