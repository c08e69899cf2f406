#pragma once
// Readers for the collision kernel's inputs, with every bad value reported
// as an InputError naming file, line and field.
//
// OBB file: the RoboGPU artifact's mpnet_master format (shared data
// collision/mpnet_master_obb.csv): a header line (recognised by a first
// field that is not a number; it must have 17 columns too), then per line
//   pose, joint, centre x y z, axis 1 x y z, axis 2 x y z, axis 3 x y z,
//   half-lengths x y z                                   (17 columns; m)
// The axis vectors are the box's axes in world coordinates (obb.h: they
// become the columns of Obb::axes). Rejected: a wrong column count (a
// truncated line included), a non-number, NaN or inf, a negative pose or
// joint index, a negative half-length, and axes that are not orthonormal
// within kAxisTolerance (|A_i . A_j - delta_ij|; the file's own axes are
// good to 1e-16, and 1e-6 still admits axes printed with 7 digits).
// Either handedness is accepted: a box does not depend on it.
//
// Box file: one AABB per line, `cx,cy,cz,hx,hy,hz` (m), optional header
// line (a first line whose first field is not a number, with 6 columns).
// Half extents must be >= 0.
//
// Blank lines and a leading UTF-8 byte-order mark are skipped in both. A
// file with no data row (empty, or a header alone) is an InputError (line 0,
// field "OBB row" or "box row"): zero queries or an empty scene would run and
// report numbers for nothing. So is a directory given as the file.
#include <istream>
#include <string>
#include <vector>

#include "robocore/collision/aabb.h"
#include "robocore/collision/obb.h"

namespace rc {

inline constexpr double kAxisTolerance = 1e-6;

struct RobotObb {
  long pose = 0;
  long joint = 0;
  Obbd obb;
};

std::vector<RobotObb> ReadObbCsv(const std::string& path);
std::vector<RobotObb> ReadObbCsv(std::istream& in, const std::string& file_name);

std::vector<Aabbd> ReadBoxCsv(const std::string& path);
std::vector<Aabbd> ReadBoxCsv(std::istream& in, const std::string& file_name);

// Writes boxes in the Box file format, with a header (cx_m,...,hz_m).
void WriteBoxCsv(std::ostream& out, const std::vector<Aabbd>& boxes);

}  // namespace rc
