// Cost models on hand-computed cases (paper latencies, artifact DRAM and
// launch figures, the default SIMT instruction table):
//   one warp with lane node counts 1,2,3,4,1,2,... all in one 32-byte sector;
//   the SACT test exiting at axis k on RoboCore and TTA+-cr;
//   predication vs conditional return vs none: one thread, exact cycles,
//   and over a batch;
//   the SACT latency and warp-buffer sweeps.
#include <omp.h>

#include <gtest/gtest.h>

#include "backends/backend.h"
#include "robocore/ray_batch_recorded.h"
#include "robocore/shipped_programs.h"
#include "test_scenes.h"

namespace rc {
namespace {

constexpr std::uint64_t kBase = std::uint64_t{1} << 20;
constexpr int kDramLatency = 20 + 160 + 47;  // L1 + L2 + (100 + 20) DRAM cycles at 3500/1365

// 32 queries; lane i fetches (i % 4) + 1 nodes, every one in the sector at
// kBase (byte i of it). No exits.
KernelRecord OneWarpRecord(const std::string& loop_body) {
  KernelRecordBuilder b(test::Program("loop:\n  LOAD c, a\n" + loop_body), StepProgramKind::kDdaStep,
                        test::ByteRegion(kBase, 64));
  for (int lane = 0; lane < 32; ++lane) b.AddQuery(std::vector<std::uint64_t>((lane % 4) + 1, kBase + lane));
  return b.Build();
}

BatchCost PriceOn(const std::string& name, const KernelRecord& record, const BackendParameters& params = {}) {
  return Backend::Create(name, params)->Price(record);
}

TEST(SimtCost, OneWarpWithKnownLaneStepCounts) {
  const BatchCost c = PriceOn("simt", OneWarpRecord("  ADD.1 x, x, y\n  RETURN_IF x\n"));
  // A pass: LOAD 6 + ADD.1 1 + RETURN_IF 1 + loop branch 2 = 10 instructions.
  // The warp runs 4 steps (its slowest lane): 40 warp instructions; its
  // lanes run 8 * (1+2+3+4) = 80 passes: 800 thread instructions.
  EXPECT_EQ(c.warp_instructions, 40u);
  EXPECT_EQ(c.thread_instructions, 800u);
  EXPECT_DOUBLE_EQ(c.simt_efficiency, 800.0 / (32.0 * 40.0));
  // One sector per step: DRAM once, then three L1 hits.
  EXPECT_EQ(c.memory.sector_requests, 4u);
  EXPECT_EQ(c.memory.l1_hits, 3u);
  EXPECT_EQ(c.memory.dram_accesses, 1u);
  // A custom program has no compiled kernel: the per-op fallback gives the
  // pass's classes (double precision, the record's default): LOAD = 1 load
  // (no latency beyond the memory's) + 5 int (4 cycles each), ADD.1 1 FP64
  // (8), RETURN_IF and the 2 loop branches 3 x 1 cycle: 31 cycles a pass.
  // Latency: 4 steps x 31 + 227 + 3 x 20 = 411; issue (10) and the pipes'
  // and L1's bounds are lower. Plus the 5000-cycle launch.
  EXPECT_EQ(c.cycles, 5000u + 411u);
  EXPECT_EQ(c.bound, "latency (resident warps)");
  EXPECT_DOUBLE_EQ(c.seconds, 5411.0 / 1365e6);
  // Energy (pJ): arithmetic 80 x (0.9 + 0.1); icache 40 x 20; registers
  // 800 x 1.5 x 10; L1 4 x 4 x 20; L2 1 x 4 x 100; DRAM 1 x 4 x 1950.
  EXPECT_NEAR(c.energy_joules, (80 + 800 + 12000 + 320 + 400 + 7800) * 1e-12, 1e-15);
  EXPECT_EQ(c.micro_ops[static_cast<int>(Opcode::kAdd)], 80u);
}

TEST(RtUnitCost, OneWarpOnTtaPlusCrAndPlain) {
  const KernelRecord r = OneWarpRecord("  ADD.1 x, x, y\n  RETURN_IF x\n");
  const BatchCost cr = PriceOn("ttaplus-cr", r);
  // A pass: ADD 3 + hop 1 + RETURN 1 = 5. Lane 0 (1 node) takes the DRAM
  // miss: 5 + 227 = 232, the warp's slowest thread; lanes after it hit L1.
  // The warp enters in ceil(32 / (4 sets x 2)) = 4 cycles.
  EXPECT_EQ(cr.launch_cycles, 5000u + 3u);  // + LOAD, ADD, RETURN_IF into the program store
  EXPECT_EQ(cr.cycles, 5003u + 4u + 5u + kDramLatency);
  EXPECT_EQ(cr.memory.sector_requests, 80u);  // no coalescing in the RT unit
  EXPECT_EQ(cr.memory.l1_hits, 79u);
  EXPECT_EQ(cr.interconnect_hops, 80u);
  EXPECT_TRUE(cr.simt_efficiency != cr.simt_efficiency);  // not meaningful here
  // Energy (pJ): arithmetic 80; packets (160 micro-ops + 2 x 80 hops) x 10;
  // warp buffer 32 x 4 x 10; L1 80 x 4 x 20; L2 400; DRAM 7800.
  EXPECT_NEAR(cr.energy_joules, (80 + 1600 + 1600 + 1280 + 6400 + 400 + 7800) * 1e-12, 1e-15);

  const BatchCost plain = PriceOn("ttaplus", r);  // RETURN_IF dropped: a pass is ADD 3
  EXPECT_EQ(plain.cycles, 5002u + 4u + 3u + kDramLatency);
  EXPECT_EQ(plain.interconnect_hops, 0u);
}

TEST(RtUnitCost, PredicationVersusConditionalReturnOverABatch) {
  // Every query's last pass fires RETURN_IF #0; two MULs follow it.
  KernelRecordBuilder b(test::Program("loop:\n  LOAD c, a\n  ADD.1 x, x, y\n  RETURN_IF x\n"
                                      "  MUL m, x, y\n  MUL m, m, y\n"),
                        StepProgramKind::kDdaStep, test::ByteRegion(kBase, 4096));
  std::uint64_t nodes = 0;
  for (int q = 0; q < 256; ++q) {
    const int n = 1 + q % 7;
    std::vector<std::uint64_t> a(n);
    std::vector<std::uint8_t> e(n, kNoExit);
    for (int k = 0; k < n; ++k) a[k] = kBase + (q * 13 + k * 64) % 4096;
    e.back() = 0;
    b.AddQuery(a, e);
    nodes += n;
  }
  const KernelRecord r = b.Build();
  const BatchCost plain = PriceOn("ttaplus", r), p = PriceOn("ttaplus-p", r), cr = PriceOn("ttaplus-cr", r),
                  robo = PriceOn("robocore", r);
  const int mul = static_cast<int>(Opcode::kMul);
  EXPECT_EQ(plain.micro_ops[mul], 2 * nodes);
  EXPECT_EQ(p.micro_ops[mul], 2 * (nodes - 256));
  EXPECT_EQ(cr.micro_ops[mul], 2 * (nodes - 256));
  EXPECT_EQ(p.predicated_off_micro_ops, 2u * 256u);
  EXPECT_EQ(cr.predicated_off_micro_ops, 0u);
  EXPECT_EQ(plain.predicated_off_micro_ops, 0u);
  // Exit pass: plain 3 + 6 + 5 = 14; -p 3 + 2 + 2 + 1 = 8; -cr 3 + 2 = 5.
  EXPECT_LT(cr.cycles - cr.launch_cycles, p.cycles - p.launch_cycles);
  EXPECT_LT(cr.energy_joules, p.energy_joules);
  // (Plain TTA+ can still beat -p: it runs no RETURN micro-op per pass.)
  // No SACT micro-ops: RoboCore times the passes as TTA+-cr does.
  EXPECT_EQ(robo.cycles - robo.launch_cycles, cr.cycles - cr.launch_cycles);
}

// One thread, two passes over nodes in one sector; the second pass fires
// RETURN_IF #0, and two MULs follow it. Hand-computed pass costs (ADD 3,
// MUL 5, RETURN 1, hop 1, a predicated micro-op 1 in its unit):
//   pass without exit    plain 3 + (1 + 5) + 5 = 14 (RETURN_IF dropped);
//                        -p and -cr 3 + (1 + 1) + (1 + 5) + 5 = 16;
//   pass with the exit   plain 14; -p 3 + 2 + (1 + 1) + 1 = 8; -cr 3 + 2 = 5.
// Thread: intake 1 cycle + its passes + DRAM (first fetch) + L1 (second).
TEST(RtUnitCost, OneThreadPredicationVersusConditionalReturn) {
  KernelRecordBuilder b(test::Program("loop:\n  LOAD c, a\n  ADD.1 x, x, y\n  RETURN_IF x\n"
                                      "  MUL m, x, y\n  MUL m, m, y\n"),
                        StepProgramKind::kDdaStep, test::ByteRegion(kBase, 64));
  b.AddQuery({kBase, kBase + 1}, {kNoExit, 0});
  const KernelRecord r = b.Build();
  const BatchCost plain = PriceOn("ttaplus", r), p = PriceOn("ttaplus-p", r), cr = PriceOn("ttaplus-cr", r);
  const std::uint64_t memory = kDramLatency + 20;
  EXPECT_EQ(plain.cycles - plain.launch_cycles, 1 + 14 + 14 + memory);
  EXPECT_EQ(p.cycles - p.launch_cycles, 1 + 16 + 8 + memory);
  EXPECT_EQ(cr.cycles - cr.launch_cycles, 1 + 16 + 5 + memory);
  const int mul = static_cast<int>(Opcode::kMul);
  EXPECT_EQ(plain.micro_ops[mul], 4u);
  EXPECT_EQ(p.micro_ops[mul], 2u);
  EXPECT_EQ(p.predicated_off_micro_ops, 2u);
  EXPECT_EQ(cr.micro_ops[mul], 2u);
  EXPECT_EQ(cr.predicated_off_micro_ops, 0u);
}

// The shipped SACT test on one node, exiting at axis k.
KernelRecord SactRecord(std::uint8_t exit) {
  KernelRecordBuilder b(ShippedStepProgram(StepProgramKind::kSactTest), StepProgramKind::kSactTest,
                        test::ByteRegion(kBase, 64));
  b.AddQuery({kBase}, {exit});
  return b.Build();
}

TEST(RtUnitCost, SactQueryExitingAtAxisKRoboCoreVersusTtaPlus) {
  for (int k = 0; k < 15; ++k) {
    const KernelRecord r = SactRecord(static_cast<std::uint8_t>(k));
    const BatchCost robo = PriceOn("robocore", r), tta = PriceOn("ttaplus-cr", r);
    // One thread: intake 1 cycle + its DRAM fetch + the test.
    const std::uint64_t robo_test = k < 6 ? 14 + 12 * (k + 1) : 14 + 72 + 12 * (k - 5);
    const std::uint64_t tta_test = k < 6 ? 27 + 33 * (k + 1) : 27 + 198 + 17 * (k - 5);
    EXPECT_EQ(robo.cycles - robo.launch_cycles, 1 + kDramLatency + robo_test) << k;
    EXPECT_EQ(tta.cycles - tta.launch_cycles, 1 + kDramLatency + tta_test) << k;
    EXPECT_EQ(robo.ctrl_exits, static_cast<std::uint64_t>(k + 1));
    EXPECT_EQ(robo.interconnect_hops, 0u);
    EXPECT_LT(robo.energy_joules, tta.energy_joules) << k;
  }
  // Launch: kernel + lowered program into the store + one decode layout.
  EXPECT_EQ(PriceOn("robocore", SactRecord(0)).launch_cycles, 5000u + 33u + 1u);
  EXPECT_EQ(PriceOn("ttaplus-cr", SactRecord(0)).launch_cycles, 5000u + 64u);
}

TEST(RtUnitCost, SactLatencySweepScalesRoboCoresTest) {
  BackendParameters slow;
  slow.robocore.sact_latency_scale = 2.0;
  const BatchCost base = PriceOn("robocore", SactRecord(kNoExit));
  const BatchCost doubled = PriceOn("robocore", SactRecord(kNoExit), slow);
  EXPECT_EQ(doubled.cycles - base.cycles, 194u);  // 14 + 72 + 108 more
}

TEST(RtUnitCost, ALargerWarpBufferHidesMoreLatency) {
  const KernelRecord record =
      test::RecordedFan(test::RoomGrid(100, 80, 0.1, 0.02, 21), RayCastMethod::kDda, 64, 32, 8.0, 22);
  BackendParameters one, eight;
  one.ttaplus.unit.warp_buffer_warps = 1;
  eight.ttaplus.unit.warp_buffer_warps = 8;
  EXPECT_GT(PriceOn("ttaplus", record, one).cycles, PriceOn("ttaplus", record).cycles);
  EXPECT_GE(PriceOn("ttaplus", record).cycles, PriceOn("ttaplus", record, eight).cycles);
}

TEST(Pricing, ASharedContextGivesTheSameCosts) {
  const KernelRecord record =
      test::RecordedFan(test::RoomGrid(60, 60, 0.1, 0.05, 31), RayCastMethod::kMarch, 20, 20, 5.0, 32);
  std::vector<std::unique_ptr<Backend>> owned;
  std::vector<const Backend*> backends;
  for (const std::string& name : Backend::ModelledNames()) {
    owned.push_back(Backend::Create(name, {}));
    backends.push_back(owned.back().get());
  }
  // PriceAll announces every backend first, so the RT units share one pass
  // over the queries; on a context that nobody announced to, each unit
  // asks in turn and the first one's pass serves only itself.
  const auto shared = PriceAll(backends, record);
  PricingContext unannounced(record);
  for (std::size_t i = 0; i < backends.size(); ++i) {
    const BatchCost alone = backends[i]->Price(record);
    for (const BatchCost* other : {&shared[i], static_cast<const BatchCost*>(nullptr)}) {
      const BatchCost c = other ? *other : backends[i]->Price(record, unannounced);
      EXPECT_EQ(c.cycles, alone.cycles) << alone.backend;
      EXPECT_EQ(c.energy_joules, alone.energy_joules) << alone.backend;
      EXPECT_EQ(c.bound, alone.bound) << alone.backend;
      EXPECT_EQ(c.micro_ops, alone.micro_ops) << alone.backend;
      EXPECT_EQ(c.nodes_counted, alone.nodes_counted) << alone.backend;
    }
  }
}

// Nodes wider than a sector (the octree's will be 432 bytes): each fetch
// requests every sector it spans, and waits for the slowest.
TEST(Pricing, WideNodesRequestEverySectorTheySpan) {
  MemoryRegion region = test::ByteRegion(kBase, 64);
  region.element_bytes = 64;  // two 32-byte sectors per node
  KernelRecordBuilder b(test::Program("loop:\n  LOAD c, a\n  ADD.1 x, x, y\n"), StepProgramKind::kSactTest, region);
  for (int lane = 0; lane < 32; ++lane) b.AddQuery({kBase + 64 * static_cast<std::uint64_t>(lane % 4)});
  const KernelRecord r = b.Build();
  const BatchCost rt = PriceOn("ttaplus-cr", r), simt = PriceOn("simt", r);
  EXPECT_EQ(rt.memory.sector_requests, 64u);   // 32 fetches x 2 sectors
  EXPECT_EQ(rt.memory.dram_accesses, 8u);      // 4 distinct nodes x 2 sectors
  EXPECT_EQ(simt.memory.sector_requests, 8u);  // one warp step, 8 unique sectors
  // The thread that first touches a node waits for DRAM once (its two
  // sectors in parallel): intake 4 + ADD 3 + 227.
  EXPECT_EQ(rt.cycles - rt.launch_cycles, 4u + 3u + kDramLatency);
}

TEST(Pricing, DoesNotDependOnTheThreadCount) {
  // A 17.6 KiB grid: the L1's cold path.
  const KernelRecord record =
      test::RecordedFan(test::RoomGrid(150, 120, 0.1, 0.03, 51), RayCastMethod::kDda, 40, 64, 8.0, 52);
  BackendParameters small_l1;  // forces the LRU path
  small_l1.gpu.l1_bytes = 4096;
  const int threads = omp_get_max_threads();
  for (const BackendParameters& params : {BackendParameters{}, small_l1})
    for (const char* name : {"simt", "ttaplus-cr"}) {
      omp_set_num_threads(1);
      const BatchCost one = PriceOn(name, record, params);
      omp_set_num_threads(3);
      const BatchCost three = PriceOn(name, record, params);
      EXPECT_EQ(one.cycles, three.cycles) << name;
      EXPECT_EQ(one.memory.l1_hits, three.memory.l1_hits) << name;
      EXPECT_EQ(one.memory.dram_accesses, three.memory.dram_accesses) << name;
    }
  omp_set_num_threads(threads);
}

}  // namespace
}  // namespace rc
