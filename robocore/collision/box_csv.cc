#include "robocore/collision/box_csv.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>

#include "common/input_error.h"
#include "common/text_fields.h"

namespace rc {
namespace {

const char* const kObbColumns[17] = {
    "pos",         "joint",       "obb_center_x",      "obb_center_y",      "obb_center_z",     "obb_axis_x1",
    "obb_axis_y1", "obb_axis_z1", "obb_axis_x2",       "obb_axis_y2",       "obb_axis_z2",      "obb_axis_x3",
    "obb_axis_y3", "obb_axis_z3", "obb_half_length_x", "obb_half_length_y", "obb_half_length_z"};
const char* const kBoxColumns[6] = {"cx", "cy", "cz", "hx", "hy", "hz"};

bool IsBlank(const std::string& line) { return line.find_first_not_of(" \t") == std::string::npos; }

void CheckColumnCount(const LineReader& reader, const std::vector<std::string_view>& fields, std::size_t expected,
                      const char* what) {
  if (fields.size() != expected)
    reader.Fail("columns", std::string(what) + ": expected " + std::to_string(expected) +
                               " comma-separated columns, found " + std::to_string(fields.size()) +
                               (fields.size() < expected ? " (truncated line?)" : ""));
}

std::ifstream Open(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open file");
  return in;
}

}  // namespace

std::vector<RobotObb> ReadObbCsv(std::istream& in, const std::string& file_name) {
  LineReader reader(in, file_name);
  std::vector<RobotObb> out;
  std::string line;
  bool first = true;
  while (reader.Next(line)) {
    if (IsBlank(line)) continue;
    const std::vector<std::string_view> f = SplitFields(line, true);
    if (first && !LooksNumeric(f.front())) {  // the header
      CheckColumnCount(reader, f, 17, "header");
      first = false;
      continue;
    }
    first = false;
    CheckColumnCount(reader, f, 17, "OBB row");
    RobotObb r;
    r.pose = reader.ParseInt(f[0], kObbColumns[0], 0, std::numeric_limits<long>::max());
    r.joint = reader.ParseInt(f[1], kObbColumns[1], 0, std::numeric_limits<long>::max());
    double v[17];
    for (int k = 2; k < 17; ++k) v[k] = reader.ParseDouble(f[k], kObbColumns[k]);
    for (int j = 0; j < 3; ++j) {
      r.obb.centre[j] = v[2 + j];
      r.obb.half[j] = v[14 + j];
      if (r.obb.half[j] < 0) reader.Fail(kObbColumns[14 + j], "negative half-length");
      for (int i = 0; i < 3; ++i) r.obb.axes(j, i) = v[5 + 3 * i + j];  // axis i -> column i
    }
    for (int i = 0; i < 3; ++i)
      for (int k = i; k < 3; ++k) {
        const double dot = r.obb.axes.col(i).dot(r.obb.axes.col(k));
        if (std::abs(dot - (i == k ? 1.0 : 0.0)) > kAxisTolerance)
          reader.Fail(kObbColumns[5 + 3 * k], i == k
                                                  ? "axis " + std::to_string(i + 1) +
                                                        " is not a unit vector (|axis|^2 = " + std::to_string(dot) + ")"
                                                  : "axes " + std::to_string(i + 1) + " and " + std::to_string(k + 1) +
                                                        " are not orthogonal (dot = " + std::to_string(dot) + ")");
      }
    out.push_back(r);
  }
  if (out.empty()) throw InputError(file_name, 0, "OBB row", "holds no OBB row (17 columns: pos, joint, ...)");
  return out;
}

std::vector<RobotObb> ReadObbCsv(const std::string& path) {
  std::ifstream in = Open(path);
  return ReadObbCsv(in, path);
}

std::vector<Aabbd> ReadBoxCsv(std::istream& in, const std::string& file_name) {
  LineReader reader(in, file_name);
  std::vector<Aabbd> out;
  std::string line;
  bool first = true;
  while (reader.Next(line)) {
    if (IsBlank(line)) continue;
    const std::vector<std::string_view> f = SplitFields(line, true);
    if (first && !LooksNumeric(f.front())) {  // the optional header
      CheckColumnCount(reader, f, 6, "header");
      first = false;
      continue;
    }
    first = false;
    CheckColumnCount(reader, f, 6, "box row");
    Aabbd box;
    for (int j = 0; j < 3; ++j) {
      box.centre[j] = reader.ParseDouble(f[j], kBoxColumns[j]);
      box.half[j] = reader.ParseDouble(f[3 + j], kBoxColumns[3 + j]);
      if (box.half[j] < 0) reader.Fail(kBoxColumns[3 + j], "negative half extent");
    }
    out.push_back(box);
  }
  if (out.empty()) throw InputError(file_name, 0, "box row", "holds no box (no 'cx,cy,cz,hx,hy,hz' row)");
  return out;
}

std::vector<Aabbd> ReadBoxCsv(const std::string& path) {
  std::ifstream in = Open(path);
  return ReadBoxCsv(in, path);
}

void WriteBoxCsv(std::ostream& out, const std::vector<Aabbd>& boxes) {
  out << "cx_m,cy_m,cz_m,hx_m,hy_m,hz_m\n" << std::setprecision(17);
  for (const Aabbd& b : boxes)
    out << b.centre[0] << ',' << b.centre[1] << ',' << b.centre[2] << ',' << b.half[0] << ',' << b.half[1] << ','
        << b.half[2] << '\n';
}

}  // namespace rc
