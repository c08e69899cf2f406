// The artifact preset (backends/presets/artifact.json, docs/artifact_preset.md)
// and the kernel-side choices it makes: the preset parses and holds the
// artifact's values, every key it sets is cited in the doc, a bad "kernel"
// object is an error naming the key, the artifact's march program keeps the
// ray-cast exit contract with the artifact's seven micro-ops, and a record
// with 8-byte cells and that program has the same hits and exits as the
// shipped one, only its addresses and program differ (and the CUDA cores
// still price the compiled march kernel).
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "backends/backend_preset.h"
#include "backends/simt_backend.h"
#include "common/input_error.h"
#include "maps/office_map_generator.h"
#include "robocore/ray_batch_recorded.h"
#include "robocore/shipped_programs.h"
#include "support/input_error_expectations.h"

namespace rc {
namespace {

std::string ReadSource(const std::string& relative) {
  std::ifstream in(std::string(RC_SOURCE_DIR) + "/" + relative);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ArtifactPreset, HoldsTheArtifactsValues) {
  const BackendPreset p = ArtifactPreset();
  EXPECT_EQ(p.name, "artifact");
  EXPECT_EQ(p.backend.gpu.l1_bytes, 8192);    // -gpgpu_cache:dl1 S:1:128:64
  EXPECT_EQ(p.backend.gpu.l2_bytes, 524288);  // 4 sub-partitions x S:64:128:16
  EXPECT_EQ(p.backend.simt.precision, SimtPrecision::kFp64);
  EXPECT_EQ(p.backend.robocore.unit.latencies.box_normal_cycles, 16);   // clusterA
  EXPECT_EQ(p.backend.robocore.unit.latencies.edge_edge_cycles, 16);    // clusterB
  EXPECT_EQ(p.backend.robocore.unit.latencies.pre_process_cycles, 16);  // clusterC
  EXPECT_EQ(p.backend.ttaplus.unit.latencies.box_normal_cycles, 12);    // dot
  // The SACT clusters take a packet every cycle (-gpgpu_rt_init_cycles 1).
  const DatapathConfig d = p.backend.robocore.Datapath();
  EXPECT_EQ(d.pre_process_initiation_cycles, 1);
  EXPECT_EQ(d.box_normal_initiation_cycles, 1);
  EXPECT_EQ(d.edge_edge_initiation_cycles, 1);
  EXPECT_EQ(p.kernel.grid_cell_bytes, 8u);
  EXPECT_EQ(p.kernel.march_program, MarchProgramChoice::kArtifact);
  EXPECT_EQ(DefaultPreset().kernel.grid_cell_bytes, 1u);
}

// `--backend-params artifact` and `--backend-params default` name the
// presets; anything else is a file, checked like any parameter file.
TEST(ArtifactPreset, LoadsByNameAndFilesAreStillChecked) {
  EXPECT_EQ(LoadBackendPreset("artifact").backend.gpu.l1_bytes, 8192);
  EXPECT_EQ(LoadBackendPreset("artifact").kernel.grid_cell_bytes, 8u);
  EXPECT_EQ(LoadBackendPreset("default").backend.gpu.l1_bytes, BackendParameters{}.gpu.l1_bytes);
  EXPECT_THROW(LoadBackendPreset("/nonexistent/artifact"), InputError);
  EXPECT_THROW(ParseBackendPreset(R"({"gpu": {"l1_bytes": 1}})", "p.json"), InputError);
}

TEST(ArtifactPreset, EmbeddedCopyEqualsTheFile) {
  EXPECT_EQ(ReadSource("backends/presets/artifact.json"), ArtifactPresetJson()) << "rebuild to re-embed";
}

// Every value the preset sets is cited in the doc's table as `struct.key`.
TEST(ArtifactPreset, EveryKeyIsCitedInTheDoc) {
  const std::string doc = ReadSource("docs/artifact_preset.md");
  ASSERT_FALSE(doc.empty()) << "docs/artifact_preset.md";
  const nlohmann::json j = nlohmann::json::parse(ArtifactPresetJson());
  for (auto s = j.begin(); s != j.end(); ++s)
    for (auto k = s.value().begin(); k != s.value().end(); ++k)
      EXPECT_NE(doc.find("`" + s.key() + "." + k.key() + "`"), std::string::npos) << s.key() << "." << k.key();
}

TEST(ArtifactPreset, BadKernelChoicesNameTheKey) {
  auto error_key = [](const std::string& json) {
    return std::string(test::InputErrorFrom([&] { ParseBackendPreset(json, "p.json"); }, json).what());
  };
  EXPECT_NE(error_key(R"({"kernel": {"grid_cell_bytes": 3}})").find("kernel.grid_cell_bytes"), std::string::npos);
  EXPECT_NE(error_key(R"({"kernel": {"grid_cell_bytes": "8"}})").find("kernel.grid_cell_bytes"), std::string::npos);
  EXPECT_NE(error_key(R"({"kernel": {"march_program": "fast"}})").find("kernel.march_program"), std::string::npos);
  EXPECT_NE(error_key(R"({"kernel": {"cells": 8}})").find("kernel.cells"), std::string::npos);
  EXPECT_NE(error_key(R"({"gpu": {"smz": 8}})").find("gpu.smz"), std::string::npos);
  EXPECT_NE(error_key(R"({"kernel": 8})").find("kernel"), std::string::npos);
  const BackendPreset p = ParseBackendPreset(R"({"gpu": {"sms": 4}, "kernel": {"grid_cell_bytes": 4}})", "p.json");
  EXPECT_EQ(p.backend.gpu.sms, 4);
  EXPECT_EQ(p.kernel.grid_cell_bytes, 4u);
  EXPECT_EQ(p.kernel.march_program, MarchProgramChoice::kShipped);
}

// SUB, RCP, DOT, CMP, OR, CMP, OR per cell (vulkan_ray_tracing.cc, node
// configuration 10), the same seven in the root pass, and the exit contract.
TEST(ArtifactMarchProgram, HasTheArtifactsSevenOpsAndKeepsTheExitContract) {
  const auto p = ShippedProgram("grid_march_artifact.asm");
  const std::vector<Opcode> seven = {Opcode::kSub, Opcode::kRcp, Opcode::kDot, Opcode::kCmp,
                                     Opcode::kOr,  Opcode::kCmp, Opcode::kOr};
  auto ops_of = [&](ProgramSection s) {
    std::vector<Opcode> ops;
    for (const MicroOp& op : p->section(s))
      if (op.opcode != Opcode::kLoad && op.opcode != Opcode::kReturnIf) ops.push_back(op.opcode);
    return ops;
  };
  EXPECT_EQ(ops_of(ProgramSection::kLoop), seven);
  EXPECT_EQ(ops_of(ProgramSection::kPrologue), seven);
  const auto& loop = p->section(ProgramSection::kLoop);
  EXPECT_EQ(loop.front().opcode, Opcode::kLoad);
  EXPECT_EQ(p->ReturnIfCount(ProgramSection::kLoop), 2);
  EXPECT_EQ(loop.back().opcode, Opcode::kReturnIf);
  EXPECT_TRUE(IsShippedProgramOf(StepProgramKind::kGridMarch, p));
  EXPECT_FALSE(IsShippedProgramOf(StepProgramKind::kDdaStep, p));
}

RayBatch FanOfRays(const OccupancyGrid& grid) {
  RayBatch batch;
  batch.max_range_m = 8.0;
  const std::vector<std::uint32_t> free = grid.FreeCellIndices();
  for (int i = 0; i < 64; ++i) {
    const std::uint32_t cell = free[(free.size() / 64) * static_cast<std::size_t>(i)];
    const double r = grid.resolution_m();
    batch.queries.push_back({(cell / grid.size_y() + 0.5) * r, (cell % grid.size_y() + 0.5) * r, 0.1 * i});
  }
  return batch;
}

TEST(ArtifactKernelChoices, EightByteCellsAndTheArtifactProgramChangeOnlyAddressesAndProgram) {
  const OccupancyGrid grid = GenerateOfficeMap();
  const RayBatch batch = FanOfRays(grid);
  const RayCastScene scene(grid, RayCastMethod::kMarch);
  std::vector<RayHit> plain_hits, shipped_hits, artifact_hits;
  CastRayBatch(scene, batch, plain_hits);
  KernelRecord shipped, artifact;
  CastRayBatchRecorded(scene, batch, shipped_hits, shipped);
  CastRayBatchRecorded(scene, batch, artifact_hits, artifact,
                       RecordOptionsFor(RayCastMethod::kMarch, ArtifactPreset().kernel));
  ASSERT_EQ(artifact_hits.size(), plain_hits.size());
  for (std::size_t i = 0; i < plain_hits.size(); ++i) {
    EXPECT_EQ(artifact_hits[i].range_m, plain_hits[i].range_m);
    EXPECT_EQ(artifact_hits[i].nodes, plain_hits[i].nodes);
  }
  EXPECT_EQ(artifact.node_bytes, 8u);
  EXPECT_EQ(artifact.program->name(), ShippedProgram("grid_march_artifact.asm")->name());
  EXPECT_EQ(artifact.last_exits, shipped.last_exits);
  ASSERT_EQ(artifact.fetch_addresses.size(), shipped.fetch_addresses.size());
  const std::uint64_t base1 = shipped.regions.front().base, base8 = artifact.regions.front().base;
  for (std::size_t i = 0; i < shipped.fetch_addresses.size(); ++i)
    ASSERT_EQ(artifact.fetch_addresses[i] - base8, 8 * (shipped.fetch_addresses[i] - base1)) << i;
  artifact.Validate();

  // The CUDA cores run the compiled march kernel either way.
  const SimtBackend simt(BackendParameters{});
  const SimtInstructionMix a = simt.InstructionMix(artifact), s = simt.InstructionMix(shipped);
  EXPECT_TRUE(a.compiled) << a.source;
  EXPECT_EQ(a.source, s.source);
  EXPECT_EQ(a.pass, s.pass);

  // Other methods keep their program; an impossible cell size is refused.
  const RecordOptions dda = RecordOptionsFor(RayCastMethod::kDda, ArtifactPreset().kernel);
  EXPECT_EQ(dda.program, nullptr);
  EXPECT_EQ(dda.layout.grid_cell_bytes, 8u);
  RayKernelChoices bad;
  bad.grid_cell_bytes = 3;
  EXPECT_THROW(RecordOptionsFor(RayCastMethod::kMarch, bad), std::invalid_argument);
  RecordOptions odd;
  odd.layout.grid_cell_bytes = 16;
  KernelRecord refused;
  EXPECT_THROW(CastRayBatchRecorded(scene, batch, shipped_hits, refused, odd), std::invalid_argument);
}

}  // namespace
}  // namespace rc
