// The TTA+ / RoboCore datapath: section timing (hops, early-exit modes,
// SACT lowering and CTRL), and the cycle-level function-unit simulator
// (agreement with the analytic timing, the input arbiter, axis counters).
// Expected values are worked out by hand from the paper's latencies
// (ADDSUB 3, MUL 5, CMP 1, RETURN 1, PUSH 1, Pre-Process 14, Box-Normal 12,
// Edge x Edge 12) and a 1-cycle interconnect hop.
#include <gtest/gtest.h>

#include "robocore/function_unit_simulator.h"
#include "robocore/section_timing.h"
#include "robocore/shipped_programs.h"
#include "test_scenes.h"

namespace rc {
namespace {

DatapathConfig Tta(EarlyExitMode mode) {
  DatapathConfig c;
  c.kind = DatapathKind::kTtaPlus;
  c.exit_mode = mode;
  return c;
}

DatapathConfig RoboCore() {
  DatapathConfig c;
  c.kind = DatapathKind::kRoboCore;
  c.exit_mode = EarlyExitMode::kConditionalReturn;
  return c;
}

const std::vector<MicroOp>& Loop(const std::shared_ptr<const MicroProgram>& p) {
  return p->section(ProgramSection::kLoop);
}

// LOAD, ADD, ADD (same unit: no hop), MUL, CMP, RETURN_IF #0, ADD.
const char* kHopProgram =
    "loop:\n"
    "  LOAD c, p\n"
    "  ADD.1 a, a, b\n"
    "  ADD.1 a, a, b\n"
    "  MUL m, a, b\n"
    "  CMP.1 f, m, a\n"
    "  RETURN_IF f\n"
    "  ADD.1 z, z, z\n";

TEST(SectionTiming, CountsAHopOnlyWhenTheUnitChanges) {
  const SectionTiming s(Loop(test::Program(kHopProgram)), Tta(EarlyExitMode::kConditionalReturn));
  const SectionCost& full = s.Cost(kNoExit);
  // 3 + 3 + (1+5) + (1+1) + (1+1) + (1+3)
  EXPECT_EQ(full.cycles, 20u);
  EXPECT_EQ(full.hops, 4u);
  EXPECT_EQ(full.loads, 1u);
  EXPECT_EQ(full.executed[static_cast<int>(Opcode::kAdd)], 3u);
}

TEST(SectionTiming, PredicationVersusConditionalReturnVersusNone) {
  const auto program = test::Program(kHopProgram);
  const SectionTiming cr(Loop(program), Tta(EarlyExitMode::kConditionalReturn));
  const SectionTiming p(Loop(program), Tta(EarlyExitMode::kPredication));
  const SectionTiming none(Loop(program), Tta(EarlyExitMode::kNone));
  // Conditional return: the pass ends at the RETURN_IF.
  EXPECT_EQ(cr.Cost(0).cycles, 16u);
  EXPECT_EQ(cr.Cost(0).hops, 3u);
  EXPECT_EQ(cr.Cost(0).predicated_off, 0u);
  // Predication: the last ADD still travels (hop) and takes one slot.
  EXPECT_EQ(p.Cost(0).cycles, 18u);
  EXPECT_EQ(p.Cost(0).hops, 4u);
  EXPECT_EQ(p.Cost(0).predicated_off, 1u);
  EXPECT_EQ(p.Cost(0).executed[static_cast<int>(Opcode::kAdd)], 2u);
  EXPECT_EQ(p.Cost(kNoExit).cycles, cr.Cost(kNoExit).cycles);
  // No early exit: the marker is dropped, everything runs, exit or not.
  EXPECT_EQ(none.Cost(kNoExit).cycles, 18u);  // 3 + 3 + 6 + 2 + 4
  EXPECT_EQ(none.Cost(0).cycles, none.Cost(kNoExit).cycles);
}

// The artifact's RETURN marker predicated later micro-ops off in plain TTA+
// mode, so its plain TTA+ cost an exit no more than predication did.
TEST(SectionTiming, PlainTtaPlusIsNotOptimisticAboutExits) {
  const auto sact = ShippedStepProgram(StepProgramKind::kSactTest);
  const SectionTiming plain(Loop(sact), Tta(EarlyExitMode::kNone));
  const SectionTiming pred(Loop(sact), Tta(EarlyExitMode::kPredication));
  for (int k = 0; k < 15; ++k) {
    EXPECT_EQ(plain.Cost(static_cast<std::uint8_t>(k)).cycles, plain.Cost(kNoExit).cycles);
    EXPECT_EQ(plain.Cost(static_cast<std::uint8_t>(k)).predicated_off, 0u);
  }
  // An early exit under predication saves the latency of every skipped
  // micro-op above one slot; the plain full test pays it all. (A late exit
  // can cost more under predication, which runs a RETURN per axis.)
  EXPECT_GT(plain.Cost(0).cycles, pred.Cost(0).cycles);
  EXPECT_LT(plain.Cost(14).cycles, pred.Cost(14).cycles);
  EXPECT_EQ(plain.Cost(kNoExit).cycles, 350u);  // 27 + 6*31 + 9*15 + 2
}

// One OBB-vs-AABB test that stops at separating axis k (RETURN_IF #k).
std::uint32_t RoboCoreSact(int k) { return k < 6 ? 14 + 12 * (k + 1) : 14 + 72 + 12 * (k - 5); }
std::uint32_t TtaCrSact(int k) { return k < 6 ? 27 + 33 * (k + 1) : 27 + 198 + 17 * (k - 5); }

TEST(SectionTiming, SactExitAtAxisKRoboCoreVersusTtaPlus) {
  const auto sact = ShippedStepProgram(StepProgramKind::kSactTest);
  const SectionTiming robo(Loop(sact), RoboCore());
  const SectionTiming tta(Loop(sact), Tta(EarlyExitMode::kConditionalReturn));
  for (int k = 0; k < 15; ++k) {
    const auto e = static_cast<std::uint8_t>(k);
    EXPECT_EQ(robo.Cost(e).cycles, RoboCoreSact(k)) << "axis " << k;
    EXPECT_EQ(robo.Cost(e).hops, 0u) << "the SACT chain needs no interconnect";
    EXPECT_EQ(robo.Cost(e).ctrl_exits, static_cast<std::uint32_t>(k + 1));
    EXPECT_EQ(tta.Cost(e).cycles, TtaCrSact(k)) << "axis " << k;
  }
  // Full test: the artifact's 194 cycles of SACT units, then PUSH (hop + 1).
  EXPECT_EQ(robo.Cost(kNoExit).cycles, 194u + 2u);
  EXPECT_EQ(tta.Cost(kNoExit).cycles, 380u);  // 27 + 6*33 + 9*17 + 2
  // 47 TTA+ micro-ops + 15 RETURNs + PUSH; RoboCore: PRE + 15 axes + PUSH.
  std::uint32_t tta_ops = 0, robo_ops = 0;
  for (int i = 0; i < kOpcodeCount; ++i) {
    if (static_cast<Opcode>(i) == Opcode::kLoad) continue;
    tta_ops += tta.Cost(kNoExit).executed[i];
    robo_ops += robo.Cost(kNoExit).executed[i];
  }
  EXPECT_EQ(tta_ops, 47u + 15u + 1u);
  EXPECT_EQ(robo_ops, 1u + 15u + 1u);
}

// CTRL's exit cycles are charged once, on the check that fires, as the
// artifact runs one RETURN op after the separating axis and none after the
// others; a test that reaches the last axis pays nothing for CTRL.
TEST(SectionTiming, CtrlExitCyclesAreChargedOnlyOnTheFiringCheck) {
  const auto sact = ShippedStepProgram(StepProgramKind::kSactTest);
  DatapathConfig with = RoboCore();
  with.ctrl_exit_cycles = 5;
  const SectionTiming robo(Loop(sact), RoboCore());
  const SectionTiming charged(Loop(sact), with);
  for (int k = 0; k < 15; ++k) {
    const auto e = static_cast<std::uint8_t>(k);
    EXPECT_EQ(charged.Cost(e).cycles, robo.Cost(e).cycles + 5u) << "axis " << k;
    EXPECT_EQ(charged.Cost(e).ctrl_exits, static_cast<std::uint32_t>(k + 1)) << "checks evaluated";
  }
  EXPECT_EQ(charged.Cost(kNoExit).cycles, robo.Cost(kNoExit).cycles);
}

TEST(SectionTiming, SactUnitsArePipelined) {
  const SectionTiming robo(Loop(ShippedStepProgram(StepProgramKind::kSactTest)), RoboCore());
  const SectionCost& c = robo.Cost(kNoExit);
  // 4-stage pipelines: PRE holds its unit ceil(14/4) = 4 cycles, each axis 3.
  EXPECT_EQ(c.unit_slots[static_cast<int>(OpUnit::kPreProcess)], 4u);
  EXPECT_EQ(c.unit_slots[static_cast<int>(OpUnit::kBoxNormal)], 6u * 3u);
  EXPECT_EQ(c.unit_slots[static_cast<int>(OpUnit::kEdgeEdge)], 9u * 3u);
}

TEST(FunctionUnitSimulator, ALoneThreadTakesItsAnalyticLatency) {
  const auto sact = ShippedStepProgram(StepProgramKind::kSactTest);
  for (const DatapathConfig& config : {RoboCore(), Tta(EarlyExitMode::kConditionalReturn),
                                       Tta(EarlyExitMode::kPredication), Tta(EarlyExitMode::kNone)}) {
    const SectionTiming s(Loop(sact), config);
    for (std::uint8_t e : {std::uint8_t{0}, std::uint8_t{4}, std::uint8_t{11}, kNoExit}) {
      const auto sim = SimulateFunctionUnit(s, {{e, 0}}, 2);
      EXPECT_EQ(sim.threads[0].finish_cycle, s.Cost(e).cycles) << ToString(config.exit_mode) << " exit " << int(e);
      EXPECT_EQ(sim.hops, s.Cost(e).hops);
    }
  }
  const SectionTiming hop(Loop(test::Program(kHopProgram)), Tta(EarlyExitMode::kPredication));
  EXPECT_EQ(SimulateFunctionUnit(hop, {{0, 7}}, 2).threads[0].finish_cycle, 18u + 7u);
}

TEST(FunctionUnitSimulator, CtrlCountsAxesAndEndsAtTheSeparatingOne) {
  const SectionTiming robo(Loop(ShippedStepProgram(StepProgramKind::kSactTest)), RoboCore());
  const auto sim = SimulateFunctionUnit(robo, {{0, 0}, {5, 0}, {9, 0}, {kNoExit, 0}}, 2);
  EXPECT_EQ(sim.threads[0].axes_tested, 1);
  EXPECT_EQ(sim.threads[1].axes_tested, 6);
  EXPECT_EQ(sim.threads[2].axes_tested, 10);
  EXPECT_EQ(sim.threads[3].axes_tested, 15);
  EXPECT_TRUE(sim.threads[2].exited_early);
  EXPECT_FALSE(sim.threads[3].exited_early);
}

// Thread 1's BOX arrives over the chain in the same cycle as thread 0's DOT
// arrives over the interconnect at the Box-Normal unit. Lowest-thread or
// arrival order would serve thread 0; the arbiter serves the chain first.
TEST(FunctionUnitSimulator, ArbiterGivesChainedSactPacketsPriority) {
  const auto program = test::Program(
      "loop:\n"
      "  LOAD n, a\n"
      "  PRE f, o, n\n"
      "  BOX s, f, 0\n"
      "  RETURN_IF s\n"
      "  ADD.1 x, x, y\n"
      "  DOT d, x, y\n");
  const SectionTiming s(Loop(program), RoboCore());
  // Thread 0: load 83, PRE 83-97, BOX 97-109, ADD 110-113, DOT ready at 114.
  // Thread 1: load 100, PRE 100-114, BOX ready at 114 over the chain.
  const auto sim = SimulateFunctionUnit(s, {{kNoExit, 83}, {kNoExit, 100}}, 2);
  EXPECT_EQ(sim.chain_priority_wins, 1u);
  EXPECT_EQ(sim.threads[0].finish_cycle, 114u + 3u + 12u);                // waits one BOX initiation (3)
  EXPECT_EQ(sim.threads[1].finish_cycle, 100u + s.Cost(kNoExit).cycles);  // never waits
}

TEST(FunctionUnitSimulator, ContentionStaysBetweenTheBounds) {
  const SectionTiming robo(Loop(ShippedStepProgram(StepProgramKind::kSactTest)), RoboCore());
  std::vector<SimulatedThread> threads(32, SimulatedThread{kNoExit, 20});
  const auto sim = SimulateFunctionUnit(robo, threads, 2);
  const std::uint64_t alone = robo.Cost(kNoExit).cycles + 20;
  const std::uint64_t edge_slots = 32u * robo.Cost(kNoExit).unit_slots[static_cast<int>(OpUnit::kEdgeEdge)];
  EXPECT_GE(sim.cycles, std::max(alone, edge_slots));
  EXPECT_LE(sim.cycles, 32u * alone);
  EXPECT_EQ(sim.busy_cycles[static_cast<int>(OpUnit::kEdgeEdge)], edge_slots);
}

}  // namespace
}  // namespace rc
