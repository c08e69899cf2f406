// The GPU check's query files (benchmarks/gpu/ray_cast_query_file.h,
// beam_leaf_file.h, sact_query_file.h): what the host writes is what the device harness reads, and a damaged file is
// refused with the field named. And the H100 preset the check prices under
// loads and says what it says (backends/presets/h100.json).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "backends/backend_preset.h"
#include "benchmarks/gpu/beam_leaf_file.h"
#include "benchmarks/gpu/ray_cast_query_file.h"
#include "benchmarks/gpu/sact_query_file.h"

namespace rc {
namespace {

using gpu_check::RayCastQueryFile;

RayCastQueryFile SmallFile() {
  RayCastQueryFile f;
  f.size_x = 3;
  f.size_y = 2;
  f.resolution_m = 0.1;
  f.max_range_m = 10.0;
  f.cells = {0, 1, 0, 0, 1, 0};
  f.distance_m = {0.1f, 0.0f, 0.2f, 0.1f, 0.0f, 0.3f};
  f.origin_x = {0.05, 0.25};
  f.origin_y = {0.05, 0.15};
  f.dir_x = {1.0, 0.0};
  f.dir_y = {0.0, -1.0};
  f.grid_order = {1, 0};
  for (int m = 0; m < gpu_check::kMethodCount; ++m) {
    f.host[m].range_m = {0.1f * static_cast<float>(m + 1), 0.15f};
    f.host[m].nodes = {static_cast<std::uint32_t>(m + 1), 2};
  }
  return f;
}

std::string TempPath(const char* name) { return (std::filesystem::temp_directory_path() / name).string(); }

TEST(GpuQueryFile, WhatIsWrittenIsReadBack) {
  const RayCastQueryFile f = SmallFile();
  const std::string path = TempPath("rc_gpu_query_roundtrip.bin");
  std::string error;
  ASSERT_TRUE(gpu_check::WriteQueryFile(f, path, &error)) << error;
  RayCastQueryFile g;
  ASSERT_TRUE(gpu_check::ReadQueryFile(path, &g, &error)) << error;
  EXPECT_EQ(g.size_x, 3);
  EXPECT_EQ(g.size_y, 2);
  EXPECT_EQ(g.resolution_m, 0.1);
  EXPECT_EQ(g.cells, f.cells);
  EXPECT_EQ(g.distance_m, f.distance_m);
  EXPECT_EQ(g.origin_x, f.origin_x);
  EXPECT_EQ(g.dir_y, f.dir_y);
  EXPECT_EQ(g.grid_order, f.grid_order);
  for (int m = 0; m < gpu_check::kMethodCount; ++m) {
    EXPECT_EQ(g.host[m].range_m, f.host[m].range_m);
    EXPECT_EQ(g.host[m].nodes, f.host[m].nodes);
  }
  std::filesystem::remove(path);
}

TEST(GpuQueryFile, InconsistentArraysAreNotWritten) {
  RayCastQueryFile f = SmallFile();
  f.host[2].nodes.pop_back();
  std::string error;
  EXPECT_FALSE(gpu_check::WriteQueryFile(f, TempPath("rc_gpu_query_bad.bin"), &error));
  EXPECT_NE(error.find("sizes disagree"), std::string::npos) << error;
}

TEST(GpuQueryFile, DamagedFilesAreRefusedNamingTheField) {
  const std::string path = TempPath("rc_gpu_query_damaged.bin");
  std::string error;
  ASSERT_TRUE(gpu_check::WriteQueryFile(SmallFile(), path, &error)) << error;
  const auto size = std::filesystem::file_size(path);
  RayCastQueryFile g;

  std::filesystem::resize_file(path, size - 1);  // the last answer array is short
  EXPECT_FALSE(gpu_check::ReadQueryFile(path, &g, &error));
  EXPECT_NE(error.find("rm answers: truncated"), std::string::npos) << error;

  ASSERT_TRUE(gpu_check::WriteQueryFile(SmallFile(), path, &error)) << error;
  {
    std::ofstream more(path, std::ios::binary | std::ios::app);
    more.put('x');
  }
  EXPECT_FALSE(gpu_check::ReadQueryFile(path, &g, &error));
  EXPECT_NE(error.find("bytes after the last array"), std::string::npos) << error;

  RayCastQueryFile bad_order = SmallFile();
  bad_order.grid_order = {0, 2};
  ASSERT_TRUE(gpu_check::WriteQueryFile(bad_order, path, &error)) << error;
  EXPECT_FALSE(gpu_check::ReadQueryFile(path, &g, &error));
  EXPECT_NE(error.find("grid_order: index out of range"), std::string::npos) << error;

  {
    std::ofstream garbage(path, std::ios::binary | std::ios::trunc);
    garbage << "not a query file at all";
  }
  EXPECT_FALSE(gpu_check::ReadQueryFile(path, &g, &error));
  EXPECT_NE(error.find("magic"), std::string::npos) << error;
  std::filesystem::remove(path);
}

gpu_check::SactQueryFile SmallSactFile() {
  gpu_check::SactQueryFile f;
  f.scene = "merged cubby";
  f.parallel_epsilon = 1e-6;
  f.node_centre = {0, 0, 0, -0.5, 0, 0, 0.5, 0, 0};
  f.node_half = {1, 1, 1, 0.5, 1, 1, 0.5, 1, 1};
  f.first_child = {1, 0, 1};
  f.child_count = {2, 0, 0};
  f.depth = {0, 1, 1};
  f.obb_centre = {0.2, 0, 0};
  f.obb_axes = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  f.obb_half = {0.1, 0.1, 0.1};
  f.collides = {1};
  f.colliding_box = {1};
  f.nodes_visited = {3};
  return f;
}

TEST(GpuQueryFile, ASactSceneIsReadBackAndADamagedOneRefused) {
  const std::string path = TempPath("rc_gpu_sact_roundtrip.bin");
  std::string error;
  ASSERT_TRUE(gpu_check::WriteSactFile(SmallSactFile(), path, &error)) << error;
  gpu_check::SactQueryFile g;
  ASSERT_TRUE(gpu_check::ReadSactFile(path, &g, &error)) << error;
  EXPECT_EQ(g.scene, "merged cubby");
  EXPECT_EQ(g.node_half, SmallSactFile().node_half);
  EXPECT_EQ(g.obb_axes, SmallSactFile().obb_axes);
  EXPECT_EQ(g.nodes_visited, SmallSactFile().nodes_visited);

  gpu_check::SactQueryFile outside = SmallSactFile();
  outside.first_child[0] = 2;  // children 2 and 3 of a 3-node tree
  ASSERT_TRUE(gpu_check::WriteSactFile(outside, path, &error)) << error;
  EXPECT_FALSE(gpu_check::ReadSactFile(path, &g, &error));
  EXPECT_NE(error.find("first_child: a child index is outside the tree"), std::string::npos) << error;

  ASSERT_TRUE(gpu_check::WriteSactFile(SmallSactFile(), path, &error)) << error;
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 4);
  EXPECT_FALSE(gpu_check::ReadSactFile(path, &g, &error));
  EXPECT_NE(error.find("nodes_visited: truncated"), std::string::npos) << error;
  std::filesystem::remove(path);
}

TEST(GpuQueryFile, ABeamLeafFileIsReadBackAndBadParametersRefused) {
  gpu_check::BeamLeafFile f;
  f.z_hit = 0.5;
  f.z_short = 0.05;
  f.z_max = 0.05;
  f.z_rand = 0.5;
  f.sigma_hit_m = 0.2;
  f.lambda_short_per_m = 0.1;
  f.max_range_m = 10.0;
  f.measured_m = {1.0, 10.0};
  f.host_log_density = {std::vector<double>{-1.0, -3.0}, std::vector<double>{-1.5, -3.0},
                        std::vector<double>{-1.5, -3.0}};
  const std::string path = TempPath("rc_gpu_leaf_roundtrip.bin");
  std::string error;
  ASSERT_TRUE(gpu_check::WriteBeamLeafFile(f, path, &error)) << error;
  gpu_check::BeamLeafFile g;
  ASSERT_TRUE(gpu_check::ReadBeamLeafFile(path, &g, &error)) << error;
  EXPECT_EQ(g.sigma_hit_m, 0.2);
  EXPECT_EQ(g.measured_m, f.measured_m);
  EXPECT_EQ(g.host_log_density[1], f.host_log_density[1]);

  f.sigma_hit_m = 0.0;  // the hit Gaussian needs a width
  ASSERT_TRUE(gpu_check::WriteBeamLeafFile(f, path, &error)) << error;
  EXPECT_FALSE(gpu_check::ReadBeamLeafFile(path, &g, &error));
  EXPECT_NE(error.find("beam parameters"), std::string::npos) << error;

  f.host_log_density[2].pop_back();
  EXPECT_FALSE(gpu_check::WriteBeamLeafFile(f, path, &error));
  std::filesystem::remove(path);
}

TEST(GpuQueryFile, TheH100PresetLoadsWithItsPublishedFigures) {
  const BackendPreset p = LoadBackendPreset(std::string(RC_SOURCE_DIR) + "/backends/presets/h100.json");
  EXPECT_EQ(p.backend.gpu.sms, 132);
  EXPECT_EQ(p.backend.gpu.max_warps_per_sm, 64);
  EXPECT_EQ(p.backend.gpu.l2_bytes, 50 * 1024 * 1024);
  EXPECT_EQ(p.backend.simt.fp64_units_per_scheduler, 1);
  // 10 controllers x 64 bytes x 2 transfers x 2.619 GHz: the datasheet's 3.35 TB/s.
  EXPECT_NEAR(p.backend.gpu.DramBytesPerCoreCycle() * p.backend.gpu.core_clock_hz, 3.35e12, 0.01e12);
  // What the preset does not name stays the model's default.
  EXPECT_EQ(p.backend.simt.fp64_div_latency_cycles, BackendParameters{}.simt.fp64_div_latency_cycles);
}

}  // namespace
}  // namespace rc
