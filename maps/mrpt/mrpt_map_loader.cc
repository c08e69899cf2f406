#include "maps/mrpt/mrpt_map_loader.h"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/serialization/CArchive.h>

#include "common/allocation_budget.h"
#include "common/input_error.h"
#include "common/memory_cap.h"
#include "maps/grid_size_limits.h"
#include "maps/mrpt/simplemap_grid_bound.h"
#include "maps/value_convention.h"
#include "traces/mrpt/mrpt_archive_bytes.h"

namespace rc {
namespace {

MrptGridMap FromMrpt(const mrpt::maps::COccupancyGridMap2D& source, const std::string& path,
                     const ProbabilityThresholds& thresholds) {
  const long size_x = static_cast<long>(source.getSizeX());
  const long size_y = static_cast<long>(source.getSizeY());
  if (size_x <= 0 || size_y <= 0) throw InputError(path, 0, "size", "the MRPT grid has no cells");
  CheckMapSize(path, 0, "size", size_x, size_y);
  const double resolution_m = source.getResolution();
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m))
    throw InputError(path, 0, "resolution", "must be a positive number of metres, got " + std::to_string(resolution_m));
  if (!std::isfinite(source.getXMin()) || !std::isfinite(source.getYMin()))
    throw InputError(path, 0, "x_min/y_min", "the grid's origin is not finite");
  MrptGridMap out;
  out.grid = OccupancyGrid(static_cast<int>(size_x), static_cast<int>(size_y), resolution_m, CellState::kUnknown);
  out.x_min_m = source.getXMin();
  out.y_min_m = source.getYMin();
  out.thresholds = thresholds;
  for (int cx = 0; cx < size_x; ++cx)
    for (int cy = 0; cy < size_y; ++cy) {
      const CellClass c =
          ClassifyProbabilityValue(source.getCell(cx, cy), ValueConvention::kProbabilityFree, thresholds);
      out.cell_classes.Add(c);
      out.grid.Set(cx, cy, StateOf(c));
    }
  return out;
}

// The counts and sizes MRPT would allocate from, checked against the bytes
// that are there (tests/fuzz: a 79-byte simplemap claiming 10^9 keyframes
// kept MRPT allocating for minutes). Each keyframe takes at least one byte;
// a gridmap (versions 3 to 6 as MRPT writes them: bits per cell, size_x,
// size_y, ...) stores size_x * size_y raw cells. Headers in another form
// are left to MRPT, which reads formats we do not know.
void CheckArchiveSizes(const std::vector<unsigned char>& bytes, const std::string& path, const std::string& what) {
  ArchiveObjectHead head;
  if (!ReadArchiveObjectHead(bytes, &head)) return;
  // MRPT matches a class by the name after its last "::" (so does this).
  const std::size_t colons = head.class_name.rfind("::");
  const std::string name = colons == std::string::npos ? head.class_name : head.class_name.substr(colons + 2);
  if (what == "simplemap") {
    if (name != "CSimpleMap" && name != "CSensFrameProbSequence") return;
    const std::uint32_t keyframes = ArchiveUint32(bytes, head.data_offset, path, "keyframe count");
    if (keyframes > bytes.size() - head.data_offset - 4)
      throw InputError(path, 0, "keyframe count",
                       std::to_string(keyframes) + " keyframes in " + std::to_string(bytes.size()) +
                           " bytes: corrupt or truncated simplemap");
    return;
  }
  if (name != "COccupancyGridMap2D") return;
  if (head.version < 3 || head.version > 6 || head.data_offset + 9 > bytes.size()) return;
  const unsigned bits_per_cell = bytes[head.data_offset];
  if (bits_per_cell != 8 && bits_per_cell != 16) return;
  const long size_x = ArchiveUint32(bytes, head.data_offset + 1, path, "size_x");
  const long size_y = ArchiveUint32(bytes, head.data_offset + 5, path, "size_y");
  CheckMapSize(path, 0, "size_x/size_y", size_x, size_y);
  const std::uint64_t cell_bytes = static_cast<std::uint64_t>(size_x) * size_y * (bits_per_cell / 8);
  if (cell_bytes > bytes.size())
    throw InputError(path, 0, "size_x/size_y",
                     std::to_string(size_x) + " x " + std::to_string(size_y) + " cells need " +
                         std::to_string(cell_bytes) + " bytes; the archive holds " + std::to_string(bytes.size()) +
                         ": corrupt or truncated gridmap");
}

// Deserializes one object of type T from the whole file, which must end
// exactly where the object does.
template <typename T>
void ReadWholeArchive(const std::string& path, const std::string& what, T& object) {
  const std::vector<unsigned char> bytes = ReadArchiveBytes(path, what);
  CheckArchiveSizes(bytes, path, what);
  CheckMrptCrashFields(bytes, path, what);
  mrpt::io::CMemoryStream memory;
  memory.assignMemoryNotOwn(bytes.data(), bytes.size());
  auto archive = mrpt::serialization::archiveFrom(memory);
  // MRPT sizes buffers from the counts the archive declares.
  const std::uint64_t budget = ParseBudgetBytes(bytes.size());
  try {
    ParseWithinBudget(budget, [&] { archive >> object; });
  } catch (const AllocationBudgetExceeded&) {
    throw InputError(path, 0, "",
                     "corrupt " + what + ": it declares sizes that would take more than " + DescribeBytes(budget) +
                         " of memory for " + std::to_string(bytes.size()) + " bytes");
  } catch (const std::exception& e) {
    throw InputError(path, 0, "",
                     "corrupt or truncated " + what + " (" + std::to_string(bytes.size()) +
                         " bytes uncompressed): " + MrptMessage(e.what()));
  }
  if (memory.getPosition() != bytes.size())
    throw InputError(path, 0, "",
                     std::to_string(bytes.size() - memory.getPosition()) + " bytes after the " + what +
                         " object: not a single " + what);
}

}  // namespace

MrptGridMap LoadMrptGridmap(const std::string& path, const ProbabilityThresholds& thresholds) {
  CheckProbabilityThresholds(thresholds);
  mrpt::maps::COccupancyGridMap2D grid;
  ReadWholeArchive(path, "gridmap", grid);
  return FromMrpt(grid, path, thresholds);
}

MrptGridMap LoadMrptSimplemap(const std::string& path, double resolution_m, const ProbabilityThresholds& thresholds) {
  CheckProbabilityThresholds(thresholds);
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m))
    throw UsageError("simplemap grid resolution must be a positive number of metres");
  mrpt::maps::CSimpleMap simple;
  ReadWholeArchive(path, "simplemap", simple);
  if (simple.empty()) throw InputError(path, 0, "", "the simplemap has no keyframes to build a grid from");
  // The grid grows as observations are inserted (loadFromSimpleMap first
  // clears it to MRPT's default extent); start with one cell.
  mrpt::maps::COccupancyGridMap2D grid(0.0f, static_cast<float>(resolution_m), 0.0f, static_cast<float>(resolution_m),
                                       static_cast<float>(resolution_m));
  grid.insertionOptions.maxDistanceInsertion = kSimplemapMaxDistanceInsertion_m;
  grid.insertionOptions.maxOccupancyUpdateCertainty = 0.55f;
  grid.insertionOptions.considerInvalidRangesAsFreeSpace = true;
  try {
    // MRPT grows the grid in a noexcept function, where a refused
    // allocation terminates the process: the size it can reach is checked
    // first, and the insertion runs under no allocation budget.
    CheckSimplemapGridBound(simple, grid, path);
    grid.loadFromSimpleMap(simple);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, 0, "", "MRPT could not build a grid from the simplemap: " + MrptMessage(e.what()));
  }
  return FromMrpt(grid, path, thresholds);
}

void ToMrptGrid(const OccupancyGrid& grid, double x_min_m, double y_min_m, mrpt::maps::COccupancyGridMap2D& out) {
  const double r = grid.resolution_m();
  // MRPT rounds both bounds to its cell lattice and sizes the grid by
  // round((max - min) / r), so exact bounds give exactly our size.
  out.setSize(static_cast<float>(x_min_m), static_cast<float>(x_min_m + grid.size_x() * r), static_cast<float>(y_min_m),
              static_cast<float>(y_min_m + grid.size_y() * r), static_cast<float>(r));
  if (static_cast<int>(out.getSizeX()) != grid.size_x() || static_cast<int>(out.getSizeY()) != grid.size_y() ||
      std::abs(out.getXMin() - x_min_m) > 1e-4 * r || std::abs(out.getYMin() - y_min_m) > 1e-4 * r)
    throw std::invalid_argument("MRPT placed the grid at (" + std::to_string(out.getXMin()) + ", " +
                                std::to_string(out.getYMin()) + "), " + std::to_string(out.getSizeX()) + " x " +
                                std::to_string(out.getSizeY()) + " cells, instead of (" + std::to_string(x_min_m) +
                                ", " + std::to_string(y_min_m) + "), " + std::to_string(grid.size_x()) + " x " +
                                std::to_string(grid.size_y()));
  for (int ix = 0; ix < grid.size_x(); ++ix)
    for (int iy = 0; iy < grid.size_y(); ++iy) {
      const CellState s = grid.At(ix, iy);
      out.setCell(ix, iy, s == CellState::kFree ? 1.0f : s == CellState::kOccupied ? 0.0f : 0.5f);
    }
}

void SaveMrptGridmap(const OccupancyGrid& grid, const std::string& path, double x_min_m, double y_min_m) {
  mrpt::maps::COccupancyGridMap2D out;
  ToMrptGrid(grid, x_min_m, y_min_m, out);
  const std::string temporary = path + ".partial";
  {
    mrpt::io::CFileGZOutputStream file;
    if (!file.open(temporary)) throw std::runtime_error("cannot write '" + temporary + "'");
    auto archive = mrpt::serialization::archiveFrom(file);
    archive << out;
  }
  std::filesystem::rename(temporary, path);
}

std::string DescribeMrptGridMap(const MrptGridMap& map) {
  std::ostringstream text;
  text << "MRPT cells are P(free): occupied if 1 - P(free) >= " << map.thresholds.occupied_thresh
       << ", free if <= " << map.thresholds.free_thresh << ", else unknown; "
       << "map (x, y) = MRPT world (X, Y) - (x_min, y_min) = (X, Y) - (" << map.x_min_m << ", " << map.y_min_m << ") m";
  return text.str();
}

}  // namespace rc
