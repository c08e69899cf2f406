// MRPT .gridmap / .simplemap input: the value convention and the frame
// offset checked against MRPT's own API, MRPT's example maps, and the bad
// archives that must become InputErrors.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>

#include <gtest/gtest.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include "common/input_error.h"
#include "common/memory_cap.h"
#include "delibot/synthetic_world.h"
#include "maps/mrpt/mrpt_map_dispatch.h"
#include "maps/mrpt/mrpt_map_loader.h"
#include "maps/mrpt/simplemap_grid_bound.h"
#include "mrpt/mrpt_test_data.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

// A grid written by MRPT itself, through its world-coordinate API: the
// loader must place each marked point in the matching cell of our frame.
TEST(MrptMapLoader, ValueConventionAndFrameMatchMrptsOwnApi) {
  mrpt::maps::COccupancyGridMap2D mrpt_grid(-2.0f, 2.0f, -1.0f, 3.0f, 0.1f);  // all 0.5: unknown
  ASSERT_NEAR(mrpt_grid.getXMin(), -2.0, 1e-6);
  ASSERT_NEAR(mrpt_grid.getYMin(), -1.0, 1e-6);
  mrpt_grid.setPos(1.05f, 0.15f, 0.0f);   // P(free) 0: a wall at world (1.05, 0.15)
  mrpt_grid.setPos(-1.55f, 2.45f, 1.0f);  // P(free) 1: free at world (-1.55, 2.45)
  mrpt_grid.setPos(0.35f, -0.95f, 0.4f);  // in between: unknown under the ROS thresholds
  const std::string path = test::ProgramTempPath("frame.gridmap.gz");
  {
    mrpt::io::CFileGZOutputStream file(path);
    auto archive = mrpt::serialization::archiveFrom(file);
    archive << mrpt_grid;
  }
  const MrptGridMap loaded = LoadMrptGridmap(path);
  EXPECT_DOUBLE_EQ(loaded.x_min_m, mrpt_grid.getXMin());
  EXPECT_DOUBLE_EQ(loaded.y_min_m, mrpt_grid.getYMin());
  ASSERT_EQ(loaded.grid.size_x(), static_cast<int>(mrpt_grid.getSizeX()));
  ASSERT_EQ(loaded.grid.size_y(), static_cast<int>(mrpt_grid.getSizeY()));
  EXPECT_NEAR(loaded.grid.resolution_m(), 0.1, 1e-7);
  // World (X, Y) is map (X - x_min, Y - y_min); cell = floor(map / r).
  auto cell_at_world = [&](double x, double y) {
    const double r = loaded.grid.resolution_m();
    return loaded.grid.At(static_cast<int>(std::floor((x - loaded.x_min_m) / r)),
                          static_cast<int>(std::floor((y - loaded.y_min_m) / r)));
  };
  EXPECT_EQ(cell_at_world(1.05, 0.15), CellState::kOccupied);
  EXPECT_EQ(loaded.grid.At(30, 11), CellState::kOccupied);  // (1.05 + 2, 0.15 + 1) / 0.1
  EXPECT_EQ(cell_at_world(-1.55, 2.45), CellState::kFree);
  EXPECT_EQ(cell_at_world(0.35, -0.95), CellState::kUnknown);
  EXPECT_EQ(loaded.grid.CountCells(CellState::kOccupied), 1u);
  EXPECT_EQ(loaded.grid.CountCells(CellState::kFree), 1u);
}

TEST(MrptMapLoader, SaveThenLoadKeepsCellsAndOrigin) {
  const OccupancyGrid room = test::AsymmetricRoom();
  const std::string path = test::ProgramTempPath("room.gridmap.gz");
  SaveMrptGridmap(room, path, -3.5, 2.0);
  const MrptGridMap loaded = LoadMrptGridmap(path);
  EXPECT_NEAR(loaded.x_min_m, -3.5, 1e-5);
  EXPECT_NEAR(loaded.y_min_m, 2.0, 1e-5);
  ASSERT_EQ(loaded.grid.size_x(), room.size_x());
  ASSERT_EQ(loaded.grid.size_y(), room.size_y());
  EXPECT_EQ(loaded.grid.cells(), room.cells());
}

TEST(MrptMapLoader, MalagaGridmap) {
  RC_REQUIRE_MRPT_DATASET("2006-MalagaCampus.gridmap.gz");
  const MrptGridMap map = LoadMrptGridmap(test::MrptDatasetPath("2006-MalagaCampus.gridmap.gz"));
  EXPECT_EQ(map.grid.size_x(), 1888);
  EXPECT_EQ(map.grid.size_y(), 2738);
  EXPECT_NEAR(map.grid.resolution_m(), 0.08, 1e-6);
  EXPECT_NEAR(map.x_min_m, -10.0, 1e-4);
  EXPECT_NEAR(map.y_min_m, -127.04, 1e-3);
  // Corridors far outnumber walls, and most of the bounding box was never seen.
  const std::size_t free = map.grid.CountCells(CellState::kFree);
  const std::size_t occupied = map.grid.CountCells(CellState::kOccupied);
  const std::size_t unknown = map.grid.CountCells(CellState::kUnknown);
  EXPECT_GT(occupied, 5000u);
  EXPECT_GT(free, 20 * occupied);
  EXPECT_GT(unknown, free);
}

TEST(MrptMapLoader, LocalizationDemoSimplemapBuildsAGrid) {
  RC_REQUIRE_MRPT_DATASET("localization_demo.simplemap.gz");
  const LoadedMapWithOrigin loaded = LoadMapWithMrpt(test::MrptDatasetPath("localization_demo.simplemap.gz"));
  EXPECT_EQ(loaded.map.format, "simplemap");
  EXPECT_NEAR(loaded.map.grid.resolution_m(), kSimplemapDefaultResolution_m, 1e-6);
  const std::size_t free = loaded.map.grid.CountCells(CellState::kFree);
  const std::size_t occupied = loaded.map.grid.CountCells(CellState::kOccupied);
  EXPECT_GT(occupied, 1000u);
  EXPECT_GT(free, 5 * occupied);
  // The building spans tens of metres around the log's start.
  EXPECT_GT(loaded.map.grid.extent_x_m(), 30.0);
  EXPECT_LT(loaded.origin_x_m, 0.0);
  EXPECT_LT(loaded.origin_y_m, 0.0);
}

TEST(MrptMapLoader, DispatcherRulesAndOptions) {
  const std::string path = test::ProgramTempPath("d.gridmap");
  SaveMrptGridmap(test::AsymmetricRoom(), path);
  EXPECT_EQ(LoadMapWithMrpt(path).map.format, "gridmap");
  MapLoadOptions options;
  options.convention = ValueConvention::kProbabilityOccupied;
  EXPECT_THROW(LoadMapWithMrpt(path, options), UsageError);
  options = {};
  options.resolution_m = 0.2;
  EXPECT_THROW(LoadMapWithMrpt(path, options), UsageError);  // a gridmap declares its resolution
}

TEST(MrptMapLoader, CorruptAndTruncatedMapsAreInputErrors) {
  const std::string whole = test::ProgramTempPath("whole.gridmap");
  SaveMrptGridmap(test::AsymmetricRoom(), whole);
  const std::string cut = test::ProgramTempPath("cut.gridmap");
  {
    // The saved file is gzip: truncating it breaks the gzip stream or the object.
    std::ifstream in(whole, std::ios::binary);
    std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::ofstream out(cut, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  }
  EXPECT_THROW(LoadMrptGridmap(cut), InputError);
  {
    std::ofstream out(cut, std::ios::binary);
    out << "P2\n# not an MRPT archive\n";
  }
  EXPECT_THROW(LoadMrptGridmap(cut), InputError);
  EXPECT_THROW(LoadMrptSimplemap(cut), InputError);
  EXPECT_THROW(LoadMrptGridmap(test::ProgramTempPath("missing.gridmap")), InputError);
}

// ---- Findings of tests/fuzz (their inputs are in tests/fuzz/corpus). ----

std::string WriteBytes(const std::string& name, const std::string& bytes) {
  const std::string path = test::ProgramTempPath(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string Uint32(std::uint32_t v) {
  return std::string{static_cast<char>(v & 0xFF), static_cast<char>((v >> 8) & 0xFF),
                     static_cast<char>((v >> 16) & 0xFF), static_cast<char>((v >> 24) & 0xFF)};
}

std::string ObjectHead(const std::string& class_name, int version) {
  return std::string(1, static_cast<char>(0x80 | class_name.size())) + class_name +
         std::string(1, static_cast<char>(version));
}

template <typename Load>
std::string InputErrorText(Load&& load) {
  return test::InputErrorFrom(std::forward<Load>(load)).what();
}

// zlib reports a corrupt stream as -1, which reached the reader as SIZE_MAX
// bytes read (an out-of-bounds copy).
TEST(MrptArchiveBadInput, CorruptGzipStream) {
  const std::string path =
      WriteBytes("corrupt.gridmap.gz", std::string("\x1f\x8b\x08\x00", 4) + std::string(60, '\x7f'));
  EXPECT_NE(InputErrorText([&] { LoadMrptGridmap(path); }).find("corrupt gzip stream"), std::string::npos);
}

// MRPT allocated the keyframe count of the header before finding the file
// too short: minutes of allocation for 79 bytes.
TEST(MrptArchiveBadInput, SimplemapClaimingMoreKeyframesThanBytes) {
  const std::string path = WriteBytes("huge.simplemap", ObjectHead("mrpt::maps::CSimpleMap", 1) + Uint32(1000000000) +
                                                            std::string(40, '\0'));
  EXPECT_NE(InputErrorText([&] { LoadMrptSimplemap(path); }).find("1000000000 keyframes"), std::string::npos);
}

TEST(MrptArchiveBadInput, GridmapDeclaringMoreCellsThanItHolds) {
  const std::string head = ObjectHead("mrpt::maps::COccupancyGridMap2D", 6) + std::string(1, '\x08');
  const std::string big = WriteBytes("big.gridmap", head + Uint32(100000) + Uint32(100000) + std::string(64, '\0'));
  EXPECT_NE(InputErrorText([&] { LoadMrptGridmap(big); }).find("100000 x 100000 cells"), std::string::npos);
  const std::string cut = WriteBytes("cut.gridmap", head + Uint32(1000) + Uint32(1000) + std::string(64, '\0'));
  EXPECT_NE(InputErrorText([&] { LoadMrptGridmap(cut); }).find("corrupt or truncated gridmap"), std::string::npos);
}

// The archive bytes of one object, as MRPT writes it.
std::string Serialized(const mrpt::serialization::CSerializable& object) {
  mrpt::io::CMemoryStream memory;
  mrpt::serialization::archiveFrom(memory) << object;
  return std::string(static_cast<const char*>(memory.getRawBufferData()), memory.getTotalBytesCount());
}

// A version-0 simplemap keyframe whose pose is not a 2D pose PDF (here a
// 3D one): MRPT read it as a null pointer and converted it to 3D through it.
TEST(MrptArchiveBadInput, Version0SimplemapWithA3dPoseIsAnInputError) {
  const std::string path = WriteBytes("v0_3d_pose.simplemap", ObjectHead("mrpt::maps::CSimpleMap", 0) + Uint32(1) +
                                                                  Serialized(mrpt::poses::CPose3DPDFGaussian()) +
                                                                  Serialized(mrpt::obs::CSensoryFrame()));
  const std::string text = InputErrorText([&] { LoadMrptSimplemap(path); });
  EXPECT_NE(text.find("keyframe pose 0 (not a mrpt::poses::CPosePDF)"), std::string::npos) << text;
  EXPECT_NE(text.find("'mrpt::poses::CPose3DPDFGaussian'"), std::string::npos) << text;
}

// A sensory frame holding "nullptr" where an observation belongs: MRPT
// dereferences every observation of a frame it inserts into a map.
TEST(MrptArchiveBadInput, SensoryFrameWithANullObservationIsAnInputError) {
  const std::string frame = ObjectHead("mrpt::obs::CSensoryFrame", 2) + Uint32(1) + "\x87nullptr" + "\x88";
  const std::string path =
      WriteBytes("null_observation.simplemap", ObjectHead("mrpt::maps::CSimpleMap", 1) + Uint32(1) +
                                                   Serialized(mrpt::poses::CPose3DPDFGaussian()) + frame + "\x88");
  const std::string text = InputErrorText([&] { LoadMrptSimplemap(path); });
  EXPECT_NE(text.find("observation 0 (not a mrpt::obs::CObservation)"), std::string::npos) << text;
}

// ---- The grid MRPT builds from a simplemap is bounded before MRPT grows it. ----

struct Keyframe {
  double x_m, y_m, yaw_rad;
  float range_m;  // every beam
};

// A simplemap written through MRPT's API: one 181-beam planar scan per
// keyframe, ranges as given.
mrpt::maps::CSimpleMap MakeSimplemap(const std::vector<Keyframe>& keyframes) {
  mrpt::maps::CSimpleMap simple;
  for (const Keyframe& k : keyframes) {
    auto scan = mrpt::obs::CObservation2DRangeScan::Create();
    scan->aperture = static_cast<float>(M_PI);
    scan->maxRange = 20.0f;
    scan->resizeScanAndAssign(181, k.range_m, true);
    auto frame = mrpt::obs::CSensoryFrame::Create();
    frame->insert(scan);
    auto pose = mrpt::poses::CPose3DPDFGaussian::Create();
    pose->mean = mrpt::poses::CPose3D(k.x_m, k.y_m, 0.0, k.yaw_rad, 0.0, 0.0);
    simple.insert(mrpt::poses::CPose3DPDF::Ptr(pose), frame);
  }
  return simple;
}

std::string SaveSimplemap(const std::string& name, const mrpt::maps::CSimpleMap& simple) {
  const std::string path = test::ProgramTempPath(name);
  mrpt::io::CFileGZOutputStream file(path);
  auto archive = mrpt::serialization::archiveFrom(file);
  archive << simple;
  return path;
}

SimplemapGridBound BoundFor(const mrpt::maps::CSimpleMap& simple, double resolution_m, const std::string& path) {
  const auto r = static_cast<float>(resolution_m);
  mrpt::maps::COccupancyGridMap2D grid(0.0f, r, 0.0f, r, r);
  grid.insertionOptions.maxDistanceInsertion = kSimplemapMaxDistanceInsertion_m;
  return CheckSimplemapGridBound(simple, grid, path);
}

void ExpectInsideBound(const MrptGridMap& map, const SimplemapGridBound& bound) {
  const double r = map.grid.resolution_m();
  EXPECT_GE(map.x_min_m, bound.x_min_m);
  EXPECT_GE(map.y_min_m, bound.y_min_m);
  EXPECT_LE(map.x_min_m + map.grid.size_x() * r, bound.x_max_m);
  EXPECT_LE(map.y_min_m + map.grid.size_y() * r, bound.y_max_m);
  EXPECT_LE(map.grid.size_x(), bound.size_x);
  EXPECT_LE(map.grid.size_y(), bound.size_y);
}

TEST(SimplemapGridBound, HoldsTheGridMrptBuilds) {
  const mrpt::maps::CSimpleMap simple =
      MakeSimplemap({{0.0, 0.0, 0.0, 3.0f}, {30.0, -12.0, 1.0, 25.0f}, {-25.0, 40.0, -2.0, 8.0f}});
  const std::string path = SaveSimplemap("bound.simplemap", simple);
  for (double resolution_m : {0.05, 0.25}) {
    const MrptGridMap map = LoadMrptSimplemap(path, resolution_m);
    ExpectInsideBound(map, BoundFor(simple, resolution_m, path));
  }
}

TEST(SimplemapGridBound, HoldsTheLocalizationDemo) {
  RC_REQUIRE_MRPT_DATASET("localization_demo.simplemap.gz");
  const std::string path = test::MrptDatasetPath("localization_demo.simplemap.gz");
  mrpt::maps::CSimpleMap simple;
  ASSERT_TRUE(simple.loadFromFile(path));
  const MrptGridMap map = LoadMrptSimplemap(path);
  const SimplemapGridBound bound = BoundFor(simple, kSimplemapDefaultResolution_m, path);
  ExpectInsideBound(map, bound);
  std::cout << "localization_demo.simplemap at " << kSimplemapDefaultResolution_m << " m: MRPT's grid "
            << map.grid.size_x() << " x " << map.grid.size_y() << " cells, bound " << bound.size_x << " x "
            << bound.size_y << "\n";
}

// A tests/fuzz finding: a keyframe's scan reaching 10^30 m away made MRPT
// grow the grid inside a noexcept function, where the refused allocation
// terminated the process. Now refused before MRPT inserts anything.
TEST(SimplemapGridBound, KeyframesTooFarApartAreAnInputError) {
  const std::string path =
      SaveSimplemap("far.simplemap", MakeSimplemap({{0.0, 0.0, 0.0, 3.0f}, {1e30, 0.0, 0.0, 3.0f}}));
  const InputError e = test::InputErrorFrom([&] { LoadMrptSimplemap(path, 0.25); }, path);
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.field(), "keyframe 1 pose");
  EXPECT_NE(std::string(e.what()).find("each side must be at most 100000 cells"), std::string::npos) << e.what();
}

// The fuzz finding's own input: a range of -3.9e7 m placed a beam end that
// far behind the laser.
TEST(SimplemapGridBound, NegativeOrNanRangesAreInputErrors) {
  mrpt::maps::CSimpleMap simple = MakeSimplemap({{0.0, 0.0, 0.0, 3.0f}, {1.0, 0.0, 0.0, 3.0f}});
  for (float bad : {-3.86e7f, std::nanf("")}) {
    mrpt::obs::CSensoryFrame::Ptr frame;
    mrpt::poses::CPose3DPDF::Ptr pose;
    simple.get(1, pose, frame);
    frame->getObservationByClass<mrpt::obs::CObservation2DRangeScan>()->setScanRange(2, bad);
    const std::string path = SaveSimplemap("negative.simplemap", simple);
    const InputError e = test::InputErrorFrom([&] { LoadMrptSimplemap(path, 0.25); }, "range " + std::to_string(bad));
    EXPECT_EQ(e.field(), "keyframe 1 observation 0 range 2");
    EXPECT_NE(std::string(e.what()).find("is not a distance"), std::string::npos) << e.what();
  }
}

TEST(SimplemapGridBound, AGridOverTheMemoryCapIsAnInputError) {
  // 2 km apart at 0.05 m: about 41,000 x 1,200 cells, 150 MB with MRPT's
  // resize copy, over a 64 MiB cap.
  const std::string path =
      SaveSimplemap("wide.simplemap", MakeSimplemap({{0.0, 0.0, 0.0, 3.0f}, {2000.0, 0.0, 0.0, 3.0f}}));
  const std::uint64_t cap = MemoryCapBytes();
  SetMemoryCapBytes(64ULL << 20);
  const std::string text = InputErrorText([&] { LoadMrptSimplemap(path, 0.05); });
  SetMemoryCapBytes(cap);
  EXPECT_NE(text.find("memory cap"), std::string::npos) << text;
  EXPECT_NE(text.find("keyframe 1 pose"), std::string::npos) << text;
}

}  // namespace
}  // namespace rc
