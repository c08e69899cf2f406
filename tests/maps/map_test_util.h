#pragma once
// Helpers shared by the maps tests: a private temporary folder and a check
// that a call throws InputError with the expected line and field.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.h"
#include "maps/occupancy_grid.h"

namespace rc::test {

// A fresh folder under the system temp dir, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "rc_maps_test_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string Path(const std::string& name) const { return (path_ / name).string(); }
  // Writes content verbatim (binary, so "\r\n" stays) and returns the path.
  std::string Write(const std::string& name, const std::string& content) const {
    const std::string p = Path(name);
    std::filesystem::create_directories(std::filesystem::path(p).parent_path());
    std::ofstream out(p, std::ios::binary);
    out << content;
    return p;
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Success when f() throws InputError whose line and field match and whose
// message contains problem_part.
template <typename F>
::testing::AssertionResult ThrowsInputError(F&& f, long line, const std::string& field,
                                            const std::string& problem_part) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (e.line() != line || e.field() != field || what.find(problem_part) == std::string::npos)
      return ::testing::AssertionFailure()
             << "InputError mismatch: got line " << e.line() << ", field '" << e.field()
             << "', message '" << what << "'; expected line " << line << ", field '" << field
             << "', message containing '" << problem_part << "'";
    return ::testing::AssertionSuccess() << what;
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "threw a different exception: " << e.what();
  }
  return ::testing::AssertionFailure() << "did not throw";
}

// The grid as text, one line per iy from the top (largest y) down, so that
// tests can compare against a picture: '.' free, '#' occupied, '?' unknown.
inline std::string Picture(const OccupancyGrid& g) {
  std::string out;
  for (int iy = g.size_y() - 1; iy >= 0; --iy) {
    for (int ix = 0; ix < g.size_x(); ++ix) out += ".#?"[static_cast<int>(g.At(ix, iy))];
    out += '\n';
  }
  return out;
}

// Cells that differ from their image under the two mirrors and the half
// turn: a generated map for global localization must differ clearly under
// each, or two places look alike.
struct SymmetryDifferences {
  std::size_t mirror_x = 0, mirror_y = 0, half_turn = 0;
};
inline SymmetryDifferences CountSymmetryDifferences(const OccupancyGrid& g) {
  const int sx = g.size_x(), sy = g.size_y();
  SymmetryDifferences d;
  for (int ix = 0; ix < sx; ++ix)
    for (int iy = 0; iy < sy; ++iy) {
      d.mirror_x += g.At(ix, iy) != g.At(sx - 1 - ix, iy);
      d.mirror_y += g.At(ix, iy) != g.At(ix, sy - 1 - iy);
      d.half_turn += g.At(ix, iy) != g.At(sx - 1 - ix, sy - 1 - iy);
    }
  return d;
}

}  // namespace rc::test
