// Every backend x every ray-cast kernel returns exactly the CPU reference's
// results, and every modelled backend prices the batch consistently (nodes
// counted by PUSH, sector requests, positive cycles and energy).
#include <tuple>

#include <gtest/gtest.h>

#include "backends/backend.h"
#include "test_scenes.h"

namespace rc {
namespace {

using Case = std::tuple<std::string, RayCastMethod>;

class BackendEquivalence : public ::testing::TestWithParam<Case> {};

TEST_P(BackendEquivalence, SameHitsAsTheCpuReference) {
  const auto& [name, method] = GetParam();
  const OccupancyGrid grid = test::RoomGrid(120, 90, 0.1, 0.03, 41);
  const RayCastScene scene(grid, method);
  const RayBatch batch = test::FanBatch(grid, 40, 45, 10.0, 42);
  std::vector<RayHit> reference, hits;
  CastRayBatch(scene, batch, reference);
  const auto backend = Backend::Create(name, BackendParameters{});
  const BatchCost cost = backend->Run(scene, batch, hits);
  ASSERT_EQ(hits.size(), reference.size());
  for (std::size_t i = 0; i < hits.size(); ++i) {
    ASSERT_EQ(hits[i].range_m, reference[i].range_m) << name << " query " << i;
    ASSERT_EQ(hits[i].nodes, reference[i].nodes) << name << " query " << i;
  }
  EXPECT_EQ(cost.backend, name);
  EXPECT_EQ(cost.queries, batch.queries.size());
  EXPECT_EQ(cost.nodes, TotalNodes(reference));
  EXPECT_GT(cost.host_seconds, 0.0);
  EXPECT_EQ(cost.modelled, backend->specs().has_cost_model);
  if (!cost.modelled) return;
  EXPECT_EQ(cost.nodes_counted, cost.nodes) << "one PUSH per node visited";
  EXPECT_GT(cost.cycles, cost.launch_cycles);
  EXPECT_GT(cost.energy_joules, 0.0);
  EXPECT_EQ(cost.memory.sector_requests, cost.memory.l1_hits + cost.memory.l2_accesses);
  EXPECT_EQ(cost.memory.l2_accesses, cost.memory.l2_hits + cost.memory.dram_accesses);
  if (backend->specs().has_rt_unit)
    EXPECT_EQ(cost.memory.sector_requests, cost.nodes);  // one request per node fetch
  else
    EXPECT_LE(cost.memory.sector_requests, cost.nodes);  // coalesced
}

INSTANTIATE_TEST_SUITE_P(AllBackendsAllKernels, BackendEquivalence,
                         ::testing::Combine(::testing::ValuesIn(Backend::Names()),
                                            ::testing::Values(RayCastMethod::kMarch, RayCastMethod::kDda,
                                                              RayCastMethod::kRayMarching)),
                         [](const auto& info) {
                           std::string name = std::get<0>(info.param) + "_" + ToString(std::get<1>(info.param));
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

TEST(BackendSpecs, DescribeEveryBackend) {
  for (const std::string& name : Backend::Names()) {
    const auto b = Backend::Create(name, {});
    EXPECT_EQ(b->specs().name, name);
    EXPECT_FALSE(b->specs().description.empty());
  }
  EXPECT_TRUE(Backend::Create("robocore", {})->specs().has_sact_units);
  EXPECT_FALSE(Backend::Create("ttaplus-cr", {})->specs().has_sact_units);
  EXPECT_EQ(Backend::Create("ttaplus-p", {})->specs().early_exit, EarlyExitMode::kPredication);
  EXPECT_FALSE(Backend::Create("cpu", {})->specs().has_cost_model);
}

}  // namespace
}  // namespace rc
