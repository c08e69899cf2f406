// The ball-query records on the backends: the shipped programs parse and
// keep the exit contract, every modelled backend prices a record, and the
// neighbours are the same whichever backend prices them.
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>

#include "backends/backend.h"
#include "common/input_error.h"
#include "nn_test_space.h"
#include "robocore/micro_program.h"
#include "robocore/shipped_programs.h"
#include "support/input_error_expectations.h"
#include "workloads/movebot/backend_nearest_neighbors.h"

namespace rc {
namespace {

using test::NnTestSpace;
using test::State;

TEST(BallQueryPrograms, ShippedProgramsKeepTheExitContract) {
  for (StepProgramKind kind : {StepProgramKind::kBallQueryPRay, StepProgramKind::kBallQueryPSphere}) {
    const auto program = ShippedStepProgram(kind);
    ASSERT_TRUE(program->has_loop()) << ToString(kind);
    const auto& loop = program->section(ProgramSection::kLoop);
    EXPECT_EQ(loop.front().opcode, Opcode::kLoad);
    EXPECT_EQ(program->ReturnIfCount(ProgramSection::kLoop), 2) << "exits #0 (no child) and #1 (no state)";
    int pushes = 0;
    for (const MicroOp& op : loop) pushes += op.opcode == Opcode::kPush;
    EXPECT_EQ(pushes, 1) << "one PUSH per node: the backends' node counter";
    // The embedded copy is the file in the source tree.
    std::ifstream file(ShippedProgramDirectory() + "/" + ToString(kind) + ".asm");
    ASSERT_TRUE(file) << ToString(kind);
    std::stringstream text;
    text << file.rdbuf();
    const MicroProgram from_file = ParseMicroProgram(text.str(), ToString(kind));
    EXPECT_EQ(from_file.MicroOpCount(), program->MicroOpCount());
  }
}

TEST(BallQueryPrograms, AMalformedCopyIsAClearError) {
  std::ifstream file(ShippedProgramDirectory() + "/ball_query_psphere.asm");
  std::stringstream text;
  text << file.rdbuf();
  std::string broken = text.str();
  const auto at = broken.find("DOT.3   sa, da, da");
  ASSERT_NE(at, std::string::npos);
  broken.replace(at, 3, "DOX");
  const std::string what =
      test::InputErrorFrom([&] { ParseMicroProgram(broken, "ball_query_psphere.asm"); }, "an unknown micro-op").what();
  EXPECT_NE(what.find("ball_query_psphere.asm"), std::string::npos) << what;
  EXPECT_NE(what.find("DOX"), std::string::npos) << what;
}

struct QueryRun {
  std::vector<std::vector<double>> answers;  // each answer's coordinates, in order
  KernelRecord record;
  BallQueryCounters counters;
};

// 2000 5-D states in the arm's joint box, then RRT*'s mix of queries.
QueryRun Queries(NnTestSpace& space, BallQueryFormulation f) {
  BallQueryConfig config;
  config.formulation = f;
  BackendNearestNeighbors<State> nn(
      config, [](const State& s) { return static_cast<const double*>(NnTestSpace::Values(s)); }, 5);
  nn.setDistanceFunction([&](const State& a, const State& b) { return space.Distance(a, b); });
  std::mt19937_64 rng(11);
  for (int i = 0; i < 2000; ++i) nn.add(space.Make(rng, -1.57, 1.57));
  QueryRun run;
  for (int i = 0; i < 60; ++i) {
    State q = space.Make(rng, -1.57, 1.57);
    auto keep = [&](const std::vector<State>& out) {
      std::vector<double> c;
      for (State s : out) c.insert(c.end(), NnTestSpace::Values(s), NnTestSpace::Values(s) + 5);
      run.answers.push_back(c);
    };
    std::vector<State> out{nn.nearest(q)};
    keep(out);
    nn.nearestK(q, 12, out);
    keep(out);
    nn.nearestR(q, 0.6, out);
    keep(out);
  }
  run.record = nn.TakeKernelRecord();
  run.counters = nn.counters();
  EXPECT_EQ(nn.TakeKernelRecord().query_count(), 0u) << "a take starts a new batch";
  return run;
}

TEST(BallQueryPricing, EveryModelledBackendPricesBothFormulations) {
  NnTestSpace space(5);
  for (BallQueryFormulation f : {BallQueryFormulation::kPRay, BallQueryFormulation::kPSphere}) {
    const QueryRun run = Queries(space, f);
    ASSERT_EQ(run.record.query_count(), 180u);
    EXPECT_EQ(run.counters.queries, 180u);
    EXPECT_EQ(run.record.total_nodes(), run.counters.nodes_visited);
    const BackendParameters params;
    for (const std::string& name : Backend::ModelledNames()) {
      const auto backend = Backend::Create(name, params);
      const auto& programs = backend->specs().step_programs;
      EXPECT_NE(std::find(programs.begin(), programs.end(), run.record.step_kind), programs.end()) << name;
      const BatchCost cost = backend->Price(run.record);
      EXPECT_TRUE(cost.modelled) << name;
      EXPECT_EQ(cost.queries, 180u) << name;
      EXPECT_EQ(cost.nodes, run.counters.nodes_visited) << name;
      EXPECT_EQ(cost.nodes_counted, cost.nodes) << name << ": one PUSH per node fetched";
      EXPECT_GT(cost.cycles, cost.launch_cycles) << name;
      EXPECT_GT(cost.energy_joules, 0) << name;
      EXPECT_GT(cost.memory.sector_requests, 0u) << name;
    }
  }
}

TEST(BallQueryPricing, ConditionalReturnNeverCostsMoreThanPlainTtaPlus) {
  NnTestSpace space(5);
  const QueryRun run = Queries(space, BallQueryFormulation::kPSphere);
  const BackendParameters params;
  const auto plain = Backend::Create("ttaplus", params), cr = Backend::Create("ttaplus-cr", params);
  const auto costs = PriceAll({plain.get(), cr.get()}, run.record);
  EXPECT_LE(costs[1].cycles, costs[0].cycles);
  // Nodes that exit at RETURN_IF #0 or #1 skip the insertion tail.
  EXPECT_LT(costs[1].micro_ops[static_cast<int>(Opcode::kMin)], costs[0].micro_ops[static_cast<int>(Opcode::kMin)]);
}

TEST(BallQueryPricing, SameNeighboursWhicheverBackendPricesThem) {
  // One kernel run per backend, as the planner does when it switches: the
  // answers never depend on the backend that prices the batch.
  NnTestSpace space(5);
  for (BallQueryFormulation f : {BallQueryFormulation::kPRay, BallQueryFormulation::kPSphere}) {
    std::vector<std::vector<double>> first;
    for (const std::string& name : Backend::Names()) {
      const QueryRun run = Queries(space, f);
      const auto backend = Backend::Create(name, BackendParameters{});
      const BatchCost cost = backend->Price(run.record);
      EXPECT_EQ(cost.queries, run.record.query_count()) << name;
      if (first.empty()) {
        first = run.answers;
        continue;
      }
      EXPECT_EQ(run.answers, first) << name;
    }
  }
}

}  // namespace
}  // namespace rc
