#pragma once
// MRPT .rawlog files (plain or gzip-compressed) into a SensorTrace.
//
// Both forms MRPT writes are read:
//   - actions/observations: CActionCollection, CSensoryFrame, CActionCollection,
//     ... Each action's CActionRobotMovement2D odometry increment is composed
//     onto the previous odometry pose (the first scan's odometry pose is the
//     increments before it applied to (0, 0, 0)), so every scan carries the
//     absolute odometry pose our motion model differences.
//   - observations only: a stream of CObservation objects; each
//     CObservation2DRangeScan takes the latest CObservationOdometry pose.
//     Scans before the first odometry observation have no pose and are
//     skipped (counted in TraceReadStats::skipped_records).
//
// Geometry comes from the observations, never from assumptions:
//   - beams: the scan's aperture A and N ranges span [-A/2, +A/2]
//     (MRPT's convention, N-1 intervals); a left-to-right scan is reversed so
//     beam 0 is the rightmost, as LaserGeometry requires;
//   - max range: the scan's maxRange; readings MRPT flags invalid, and
//     readings at or beyond maxRange, become max_range_m ("no return");
//   - mount: the scan's sensorPose. Its forward offset becomes
//     offset_forward_m; its yaw is added to angle_min_rad, which is exact
//     because beams are measured from the robot heading. LaserGeometry has no
//     sideways offset, so a laser more than 5 mm off the heading axis, or
//     pitched/rolled by more than 1e-3 rad, is rejected rather than silently
//     moved (as the CMU and CARMEN readers do).
//   - A SensorTrace has one geometry, so every scan must agree with the first
//     (same beam count, aperture, direction, max range and mount).
// Several lasers: only scans whose sensorLabel equals `sensor_label` are
// read; empty means the label of the first 2D scan in the file. Scans of
// other lasers and all other observations are counted as skipped.
//
// Time: seconds since the first scan read (MRPT stores epoch times, about
// 1e9 s, whose sub-second part a timeline's significant digits would lose).
//
// Errors: every problem, including MRPT's own exceptions on a corrupt or
// truncated archive, is an InputError naming the file and the rawlog entry
// (0-based object index, given as the field) and the byte offset reached;
// nothing partial is returned.
#include <string>

#include "traces/sensor_trace.h"
#include "traces/trace_read_stats.h"

namespace rc {

struct RawlogReadOptions {
  std::string sensor_label;  // empty: the first 2D range scan's label
};

SensorTrace ReadMrptRawlog(const std::string& path, const RawlogReadOptions& options = {},
                           TraceReadStats* stats = nullptr);

// True when the path names a rawlog by extension: .rawlog or .rawlog.gz.
// (Defined with the dispatch, mrpt_trace_dispatch.cc, which needs no MRPT.)
bool HasRawlogExtension(const std::string& path);

}  // namespace rc
