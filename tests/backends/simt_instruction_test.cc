// The SIMT model prices the compiled CUDA kernels: the embedded table
// (backends/simt_instruction_table.json), the counts the backend takes from
// it per shipped program, precision and ISA, the per-op fallback for
// programs with no compiled kernel, and the direction FP64 moves the cycles.
// (The table against a fresh nvcc compile: ctest simt_instruction_table_check.)
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backends/backend.h"
#include "backends/simt_backend.h"
#include "backends/simt_instruction_table.h"
#include "common/input_error.h"
#include "common/random_stream.h"
#include "robocore/collision/box_tree.h"
#include "robocore/collision/flat_box_tree.h"
#include "robocore/collision/sact_kernel_record.h"
#include "robocore/collision/tree_collision.h"
#include "robocore/ray_batch_recorded.h"
#include "robocore/shipped_programs.h"
#include "support/input_error_expectations.h"
#include "test_scenes.h"

namespace rc {
namespace {

constexpr StepProgramKind kAllKinds[] = {StepProgramKind::kGridMarch,       StepProgramKind::kDdaStep,
                                         StepProgramKind::kRmStep,          StepProgramKind::kSactTest,
                                         StepProgramKind::kSphereTest,      StepProgramKind::kBallQueryPRay,
                                         StepProgramKind::kBallQueryPSphere};

bool IsRayKind(StepProgramKind k) {
  return k == StepProgramKind::kGridMarch || k == StepProgramKind::kDdaStep || k == StepProgramKind::kRmStep;
}

// 32 queries (one warp) of `nodes` 1-byte nodes each, with the shipped step
// program of `kind` and optionally the shipped beam leaf.
KernelRecord OneWarp(StepProgramKind kind, std::uint32_t nodes, bool beam_leaf = false, std::uint8_t scalar = 8) {
  constexpr std::uint64_t kBase = std::uint64_t{1} << 32;
  KernelRecordBuilder b(ShippedStepProgram(kind), kind, test::ByteRegion(kBase, 4096));
  if (beam_leaf) b.SetLeaf(ShippedLeafProgram(LeafProgramKind::kBeamModel), LeafProgramKind::kBeamModel);
  for (int q = 0; q < 32; ++q) {
    std::vector<std::uint64_t> a;
    for (std::uint32_t k = 0; k < nodes; ++k) a.push_back(kBase + 64 * q + k);
    b.AddQuery(a);
  }
  KernelRecord r = b.Build();
  r.scalar_bytes = scalar;
  return r;
}

SimtBackend Simt(const BackendParameters& p = {}) { return SimtBackend(p); }

TEST(SimtInstructionTable, EmbeddedTableNamesItsCompilerAndCoversEveryShippedProgram) {
  const SimtInstructionTable& t = SimtInstructionTable::Shipped();
  EXPECT_NE(t.nvcc().find("release"), std::string::npos) << t.nvcc();
  EXPECT_EQ(t.arch(), "sm_75");  // the artifact's Turing configuration (compute capability 7.5)
  for (StepProgramKind kind : kAllKinds)
    for (bool fp64 : {false, true}) {
      const CompiledKernel* k = t.Find(ShippedProgramFile(kind), fp64, SimtBeamLeaf::kNone);
      ASSERT_NE(k, nullptr) << ShippedProgramFile(kind);
      EXPECT_GT(Total(k->ptx.loop), 0u) << k->name;
      EXPECT_TRUE(k->has_sass) << k->name;
      EXPECT_NE(k->name.find(fp64 ? "fp64" : "fp32"), std::string::npos) << k->name;
      // A float kernel holds no double arithmetic; a double kernel's loop
      // does (every shipped loop computes in its scalar type).
      const auto& loop = k->ptx.loop;
      if (fp64)
        EXPECT_GT(loop[int(SimtClass::kFp64)] + loop[int(SimtClass::kFp64Div)], 0u) << k->name;
      else
        EXPECT_EQ(loop[int(SimtClass::kFp64)] + loop[int(SimtClass::kFp64Div)], 0u) << k->name;
      for (SimtBeamLeaf leaf : {SimtBeamLeaf::kMaxLog, SimtBeamLeaf::kExact})
        EXPECT_EQ(t.Find(ShippedProgramFile(kind), fp64, leaf) != nullptr, IsRayKind(kind)) << k->name;
    }
}

TEST(SimtInstructionTable, MalformedTablesAreInputErrorsNamingTheKey) {
  auto key_of = [](const std::string& json) {
    const InputError e = test::InputErrorFrom([&] { SimtInstructionTable::Parse(json, "t.json"); }, json);
    EXPECT_EQ(e.file(), "t.json");
    return e.field();
  };
  EXPECT_EQ(key_of("{"), "");
  EXPECT_EQ(key_of(R"({"arch": "sm_75"})"), "nvcc");
  const std::string head = R"({"nvcc": "x", "arch": "sm_75", "classes": ["fp32","fp64","int","fp32_div",
      "fp64_div","int_div","sfu","load","store","branch","other"], "programs": )";
  const std::string counts = R"({"fp32":1,"fp64":0,"int":0,"fp32_div":0,"fp64_div":0,"int_div":0,"sfu":0,
      "load":1,"store":0,"branch":1,"other":0})";
  const std::string kernel = R"({"kernel": "k", "registers": 20, "ptx": {"prologue": )" + counts + R"(, "loop": )" +
                             counts + R"(, "epilogue": )" + counts + "}}";
  const std::string good = head + R"({"dda_step.asm": {"fp32": )" + kernel + R"(, "fp64": )" + kernel + "}}}";
  const SimtInstructionTable t = SimtInstructionTable::Parse(good, "t.json");
  ASSERT_NE(t.Find("dda_step.asm", true, SimtBeamLeaf::kNone), nullptr);
  EXPECT_EQ(Total(t.Find("dda_step.asm", true, SimtBeamLeaf::kNone)->ptx.loop), 3u);
  std::string negative = good;
  negative.replace(negative.find("\"fp32\":1"), 8, "\"fp32\":-1");
  EXPECT_EQ(key_of(negative), "programs/dda_step.asm/fp32/ptx/prologue/fp32");
  EXPECT_EQ(key_of(head + R"({"dda_step.asm": {"fp32": )" + kernel + "}}}"), "programs/dda_step.asm/fp64");
}

// The backend's counts per pass (and per query) are the table's, for every
// shipped kernel, precision, ISA, and with the beam leaf where compiled.
TEST(SimtInstructionMix, EveryShippedKernelIsPricedFromTheTable) {
  const SimtInstructionTable& t = SimtInstructionTable::Shipped();
  for (SimtIsa isa : {SimtIsa::kPtx, SimtIsa::kSass})
    for (SimtPrecision precision : {SimtPrecision::kFp32, SimtPrecision::kFp64})
      for (StepProgramKind kind : kAllKinds)
        for (SimtBeamLeaf leaf : {SimtBeamLeaf::kNone, SimtBeamLeaf::kMaxLog, SimtBeamLeaf::kExact}) {
          if (leaf != SimtBeamLeaf::kNone && !IsRayKind(kind)) continue;
          BackendParameters p;
          p.simt.precision = precision;
          p.simt.isa = isa;
          if (leaf != SimtBeamLeaf::kNone) p.simt.beam_leaf = leaf;
          const bool fp64 = precision == SimtPrecision::kFp64;
          const SimtInstructionMix mix = Simt(p).InstructionMix(OneWarp(kind, 3, leaf != SimtBeamLeaf::kNone));
          const CompiledKernel* k = t.Find(ShippedProgramFile(kind), fp64, leaf);
          ASSERT_NE(k, nullptr);
          const CompiledSections& s = isa == SimtIsa::kSass ? k->sass : k->ptx;
          SimtClassCounts once = s.prologue;
          once += s.epilogue;
          EXPECT_TRUE(mix.compiled) << mix.source;
          EXPECT_EQ(mix.pass, s.loop) << k->name;
          EXPECT_EQ(mix.once, once) << k->name;
          EXPECT_EQ(mix.registers, k->registers) << k->name;
          EXPECT_NE(mix.source.find(k->name), std::string::npos) << mix.source;
        }
}

TEST(SimtInstructionMix, WarpInstructionsAreTheCompiledSectionsTimesTheSteps) {
  const SimtBackend simt = Simt();
  const KernelRecord record = OneWarp(StepProgramKind::kDdaStep, 5, true);
  const SimtInstructionMix mix = simt.InstructionMix(record);
  const BatchCost cost = simt.Price(record);
  EXPECT_EQ(cost.warp_instructions, Total(mix.once) + 5 * Total(mix.pass));
  EXPECT_EQ(cost.thread_instructions, 32 * (Total(mix.once) + 5 * Total(mix.pass)));
  EXPECT_DOUBLE_EQ(cost.simt_efficiency, 1.0);
}

// The default leaf is the max-log computation of beam_leaf.asm, the one the
// RT backends price; the host's exact density (exp, log, divisions) costs
// the CUDA cores more, in instructions and in cycles.
TEST(SimtInstructionMix, BeamLeafDefaultsToTheRtUnitsLeafAndExactCostsMore) {
  const KernelRecord record = OneWarp(StepProgramKind::kDdaStep, 4, true);
  BackendParameters exact;
  exact.simt.beam_leaf = SimtBeamLeaf::kExact;
  const SimtInstructionMix maxlog_mix = Simt().InstructionMix(record);
  const SimtInstructionMix exact_mix = Simt(exact).InstructionMix(record);
  EXPECT_NE(maxlog_mix.source.find("rc_dda_beam_fp64"), std::string::npos) << maxlog_mix.source;
  EXPECT_NE(exact_mix.source.find("rc_dda_beam_exact_fp64"), std::string::npos) << exact_mix.source;
  EXPECT_GT(Total(exact_mix.once), Total(maxlog_mix.once));
  const SimtInstructionMix plain = Simt().InstructionMix(OneWarp(StepProgramKind::kDdaStep, 4, false));
  EXPECT_EQ(maxlog_mix.once[int(SimtClass::kFp64Div)], plain.once[int(SimtClass::kFp64Div)]);  // no division added
  EXPECT_GT(exact_mix.once[int(SimtClass::kFp64Div)], plain.once[int(SimtClass::kFp64Div)]);
  EXPECT_GT(Simt(exact).Price(record).cycles, Simt().Price(record).cycles);
  EXPECT_THROW(ParseBackendParameters(R"({"simt": {"beam_leaf": "none"}})", "p.json"), InputError);
}

TEST(SimtInstructionMix, HostPrecisionFollowsTheKernelThatRan) {
  const SimtBackend simt = Simt();                                               // simt.precision = host
  EXPECT_TRUE(simt.InstructionMix(OneWarp(StepProgramKind::kDdaStep, 2)).fp64);  // the ray casters are double
  // The collision kernel in float and in double, run through CollideBatch.
  std::vector<Aabbd> boxes;
  for (int i = 0; i < 8; ++i) boxes.push_back(Aabbd{Eigen::Vector3d(i, 0, 0), Eigen::Vector3d(0.4, 0.4, 0.4)});
  const BoxTree tree = BuildMedianSplitTree(boxes);
  Obbd obb;
  obb.centre = Eigen::Vector3d(2.2, 0.1, 0);
  obb.half = Eigen::Vector3d(0.3, 0.2, 0.1);
  const KernelRecord in_double =
      SactKernelRecord(CollideBatch(FlatBoxTree<double>(tree), std::vector<Obbd>{obb}, CollisionOptions<double>{}));
  const KernelRecord in_float = SactKernelRecord(
      CollideBatch(FlatBoxTree<float>(tree), std::vector<Obbf>{obb.Cast<float>()}, CollisionOptions<float>{}));
  EXPECT_EQ(in_double.scalar_bytes, 8);
  EXPECT_EQ(in_float.scalar_bytes, 4);
  EXPECT_NE(simt.InstructionMix(in_double).source.find("rc_sact_fp64"), std::string::npos);
  EXPECT_NE(simt.InstructionMix(in_float).source.find("rc_sact_fp32"), std::string::npos);
  BackendParameters fp32;
  fp32.simt.precision = SimtPrecision::kFp32;
  EXPECT_FALSE(Simt(fp32).InstructionMix(in_double).fp64);
}

// FP64 instructions are priced by their class (the artifact's DP timing,
// on the SFU unit), so the double kernel costs more cycles than the float
// one, on every shipped program, in PTX and in SASS.
TEST(SimtInstructionMix, Fp64CostsMoreCyclesThanFp32) {
  for (SimtIsa isa : {SimtIsa::kPtx, SimtIsa::kSass})
    for (StepProgramKind kind : kAllKinds) {
      BackendParameters p32, p64;
      p32.simt.isa = p64.simt.isa = isa;
      p32.simt.precision = SimtPrecision::kFp32;
      p64.simt.precision = SimtPrecision::kFp64;
      const KernelRecord record = OneWarp(kind, 20);
      const BatchCost c32 = Simt(p32).Price(record), c64 = Simt(p64).Price(record);
      EXPECT_GT(c64.cycles, c32.cycles) << ShippedProgramFile(kind) << " isa " << ToString(isa);
    }
  // With the FP64 ops priced as FP32 ops, the same double kernel costs less:
  // the class timing, not only the instruction count, carries the precision.
  BackendParameters as_fp32, dp;
  as_fp32.simt.precision = dp.simt.precision = SimtPrecision::kFp64;
  as_fp32.simt.fp64_latency_cycles = as_fp32.simt.fp32_latency_cycles;
  as_fp32.simt.fp64_initiation_cycles = as_fp32.simt.fp32_initiation_cycles;
  as_fp32.simt.fp64_units_per_scheduler = 1;
  const KernelRecord sact = OneWarp(StepProgramKind::kSactTest, 20);
  EXPECT_LT(Simt(as_fp32).Price(sact).cycles, Simt(dp).Price(sact).cycles);
}

// A program with no compiled kernel (a ConfigRoboCore program) is counted
// by the per-op fallback, and says so; a custom leaf on a shipped program
// adds its fallback count to the compiled kernel.
TEST(SimtInstructionMix, ProgramsWithoutACompiledKernelUseTheDeclaredFallback) {
  const SimtBackend simt = Simt();
  const std::string text =
      "loop:\n  LOAD c, p\n  PUSH v\n  CMP.2 b, c, f\n  RETURN_IF b\n  ADD.2 p, p, d\n  RETURN_IF b\n";
  const auto custom = test::Program(text, "custom.asm");
  KernelRecordBuilder b(custom, StepProgramKind::kDdaStep, test::ByteRegion(std::uint64_t{1} << 32, 64));
  b.AddQuery({std::uint64_t{1} << 32});
  const KernelRecord record = b.Build();
  const SimtInstructionMix mix = simt.InstructionMix(record);
  EXPECT_FALSE(mix.compiled);
  EXPECT_NE(mix.source.find("per-op fallback"), std::string::npos) << mix.source;
  EXPECT_NE(mix.source.find("'custom'"), std::string::npos) << mix.source;
  EXPECT_EQ(mix.pass, simt.FallbackInstructions(custom->section(ProgramSection::kLoop), true, true));
  // LOAD = 1 load + 5 address ops, PUSH 1 int, CMP.2 2 other, ADD.2 2 FP64,
  // 2 RETURN_IF + 2 loop branches.
  EXPECT_EQ(mix.pass[int(SimtClass::kLoad)], 1u);
  EXPECT_EQ(mix.pass[int(SimtClass::kInt)], 6u);
  EXPECT_EQ(mix.pass[int(SimtClass::kOther)], 2u);
  EXPECT_EQ(mix.pass[int(SimtClass::kFp64)], 2u);
  EXPECT_EQ(mix.pass[int(SimtClass::kBranch)], 4u);
  EXPECT_EQ(mix.registers, BackendParameters{}.simt.fallback_registers_per_thread);
  EXPECT_GT(simt.Price(record).cycles, 0u);

  KernelRecordBuilder with_leaf(ShippedStepProgram(StepProgramKind::kDdaStep), StepProgramKind::kDdaStep,
                                test::ByteRegion(std::uint64_t{1} << 32, 64));
  with_leaf.SetLeaf(test::Program("epilogue:\n  MUL.1 a, b, c\n  RETURN\n", "leaf.asm"), LeafProgramKind::kCustom);
  with_leaf.AddQuery({std::uint64_t{1} << 32});
  const SimtInstructionMix leaf_mix = simt.InstructionMix(with_leaf.Build());
  const SimtInstructionMix plain = simt.InstructionMix(OneWarp(StepProgramKind::kDdaStep, 1));
  EXPECT_TRUE(leaf_mix.compiled);
  EXPECT_NE(leaf_mix.source.find("leaf 'leaf' by the per-op fallback"), std::string::npos) << leaf_mix.source;
  EXPECT_EQ(Total(leaf_mix.once), Total(plain.once) + 2);  // MUL (1 FP64) + RETURN (1 branch)
  EXPECT_EQ(leaf_mix.pass, plain.pass);
}

TEST(SimtInstructionMix, RegistersFromTheKernelSetTheResidentWarps) {
  BackendParameters p;
  const CompiledKernel* sact = SimtInstructionTable::Shipped().Find("sact_obb_aabb.asm", true, SimtBeamLeaf::kNone);
  ASSERT_NE(sact, nullptr);
  // 32768 registers per SM / (registers x 32 threads), at most 32 warps.
  EXPECT_EQ(p.simt.ResidentWarps(p.gpu, sact->registers), std::min(32, 32768 / (sact->registers * 32)));
  p.simt.registers_per_thread = 16;
  EXPECT_EQ(SimtBackend(p).InstructionMix(OneWarp(StepProgramKind::kSactTest, 1)).registers, 16);
}

TEST(SimtParameters, PrecisionAndIsaAreNamedChoicesInTheOverrideFile) {
  const BackendParameters p = ParseBackendParameters(R"({"simt": {"precision": "fp32", "isa": "sass"}})", "p.json");
  EXPECT_EQ(p.simt.precision, SimtPrecision::kFp32);
  EXPECT_EQ(p.simt.isa, SimtIsa::kSass);
  for (const char* bad :
       {R"({"simt": {"precision": "double"}})", R"({"simt": {"precision": 64}})", R"({"simt": {"isa": "ptxas"}})"}) {
    const InputError e = test::InputErrorFrom([&] { ParseBackendParameters(bad, "p.json"); }, bad);
    EXPECT_NE(std::string(e.what()).find("expected one of"), std::string::npos) << e.what();
    EXPECT_EQ(e.field().rfind("simt.", 0), 0u) << e.field();
  }
  bool printed = false;
  for (const ParameterDescription& d : DescribeBackendParameters(BackendParameters{}))
    if (d.key == "simt.precision") {
      printed = true;
      EXPECT_EQ(d.value, "host");
      EXPECT_EQ(d.unit, "host | fp32 | fp64");
    }
  EXPECT_TRUE(printed);
}

}  // namespace
}  // namespace rc
