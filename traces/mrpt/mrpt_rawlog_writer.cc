#include "traces/mrpt/mrpt_rawlog_writer.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/serialization/CArchive.h>

namespace rc {
namespace {

mrpt::obs::CObservation2DRangeScan::Ptr MakeScan(const LaserScan& scan, const LaserGeometry& g) {
  auto out = mrpt::obs::CObservation2DRangeScan::Create();
  out->sensorLabel = "LASER";
  out->timestamp = mrpt::Clock::fromDouble(scan.time_s);
  out->aperture = static_cast<float>(g.angle_increment_rad * (g.beam_count - 1));
  out->rightToLeft = true;
  out->maxRange = static_cast<float>(g.max_range_m);
  out->sensorPose = mrpt::poses::CPose3D(g.offset_forward_m, 0.0, 0.0, g.angle_min_rad + 0.5 * out->aperture, 0.0, 0.0);
  out->resizeScan(scan.ranges_m.size());
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const bool valid = scan.ranges_m[i] < g.max_range_m;
    out->setScanRange(i, valid ? scan.ranges_m[i] : static_cast<float>(g.max_range_m));
    out->setScanRangeValidity(i, valid);
  }
  return out;
}

}  // namespace

void WriteMrptRawlog(const SensorTrace& trace, const std::string& path, RawlogForm form) {
  const std::string temporary = path + ".partial";
  try {
    {
      mrpt::io::CFileOutputStream file;
      if (!file.open(temporary)) throw std::runtime_error("cannot write '" + temporary + "'");
      auto archive = mrpt::serialization::archiveFrom(file);
      mrpt::poses::CPose2D previous(0, 0, 0);
      for (const LaserScan& scan : trace.scans) {
        const mrpt::poses::CPose2D odometry(scan.odometry.x, scan.odometry.y, scan.odometry.theta);
        if (form == RawlogForm::kActionsObservations) {
          mrpt::obs::CActionRobotMovement2D movement;
          movement.timestamp = mrpt::Clock::fromDouble(scan.time_s);
          movement.computeFromOdometry(odometry - previous, mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
          mrpt::obs::CActionCollection actions;
          actions.insert(movement);
          mrpt::obs::CSensoryFrame frame;
          frame.insert(MakeScan(scan, trace.geometry));
          archive << actions << frame;
        } else {
          auto odometry_observation = mrpt::obs::CObservationOdometry::Create();
          odometry_observation->sensorLabel = "ODOMETRY";
          odometry_observation->timestamp = mrpt::Clock::fromDouble(scan.time_s);
          odometry_observation->odometry = odometry;
          archive << *odometry_observation << *MakeScan(scan, trace.geometry);
        }
        previous = odometry;
      }
    }
    std::filesystem::rename(temporary, path);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

}  // namespace rc
