// Where the adaptive policy starts, before anything has been measured: the
// candidate cheapest on a start probe (BackendLedger::Prepare), and
// DeliBot's probe, the first update's batch drawn in advance
// (workloads/delibot/start_probe.h). The decisions it makes on whole runs
// are pinned in schedule_scenes_test.cc.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "backends/scheduler/backend_ledger.h"
#include "common/random_stream.h"
#include "maps/office_map_generator.h"
#include "workloads/delibot/beam_sensor_model.h"
#include "workloads/delibot/start_probe.h"

namespace rc {
namespace {

struct Office {
  OccupancyGrid grid = GenerateOfficeMap(OfficeMapOptions{});
  LaserGeometry geometry;  // 180 beams, the Wean SICK's
  BeamSelection beams{6};

  MonteCarloLocalizer Localizer(RayCastMethod method) const {
    MclOptions options;
    options.particle_count = 200;
    options.seed = 3;
    return MonteCarloLocalizer(
        grid, std::make_unique<BeamSensorModel>(std::make_shared<RayCastScene>(grid, method), BeamModelParams{}),
        options);
  }
  KernelRecord Probe(const MonteCarloLocalizer& mcl, RayCastMethod method, std::size_t poses) const {
    return CastStartProbe(mcl, RayCastScene(grid, method), geometry, beams, 10.0, poses, 3,
                          RecordOptionsFor(method, RayKernelChoices{}));
  }
};

TEST(StartProbeTest, TheLedgerStartsOnTheCandidateCheapestOnTheProbe) {
  const Office office;
  const BackendParameters params;
  std::vector<std::string> paper_pair_start;  // per ray caster, over {simt, robocore}
  for (RayCastMethod method : {RayCastMethod::kMarch, RayCastMethod::kDda}) {
    MonteCarloLocalizer mcl = office.Localizer(method);
    mcl.InitializeUniform();
    const KernelRecord probe = office.Probe(mcl, method, 200);
    for (const std::vector<std::string>& candidates :
         std::vector<std::vector<std::string>>{{}, {"simt", "robocore"}, {"ttaplus", "ttaplus-cr"}}) {
      LedgerOptions options;
      options.policy.kind = SchedulerKind::kAdaptive;
      options.policy.candidates = candidates;
      BackendLedger ledger(params, options);
      ASSERT_TRUE(ledger.ChoosesStart());
      std::vector<std::unique_ptr<Backend>> owned;
      std::vector<const Backend*> priced;
      for (const std::string& name : ledger.candidates()) {
        owned.push_back(Backend::Create(name, params));
        priced.push_back(owned.back().get());
      }
      const std::vector<BatchCost> costs = PriceAll(priced, probe);
      const auto cheapest = std::min_element(
          costs.begin(), costs.end(), [](const BatchCost& a, const BatchCost& b) { return a.cycles < b.cycles; });
      // The template (one pose's rays) gives only the layout; the probe
      // decides.
      ledger.Prepare(office.Probe(mcl, method, 1), 30, 1024, &probe);
      const std::string start = ledger.BeginIteration();
      EXPECT_EQ(start, ledger.candidates()[static_cast<std::size_t>(cheapest - costs.begin())])
          << ToString(method) << ", " << candidates.size() << " candidates";
      if (candidates.size() == 2 && candidates[0] == "simt") paper_pair_start.push_back(start);
    }
  }
  // On the office RoboCore wins every march update and SIMT every dda one
  // (schedule_scenes_test.cc); the probes say so before the first.
  EXPECT_EQ(paper_pair_start, (std::vector<std::string>{"robocore", "simt"}));
}

TEST(StartProbeTest, TheProbeIsTheFirstBatchUpToTheCap) {
  EXPECT_EQ(BackendLedger::StartProbeQueries(9000), 9000u);
  EXPECT_EQ(BackendLedger::StartProbeQueries(std::size_t{1} << 30), kStartProbeMaxQueries);
  EXPECT_EQ(StartProbePoses(300, 30), 300u);                                       // 9,000 rays: every particle
  EXPECT_EQ(StartProbePoses(10000, 30), kStartProbeMaxQueries / 30);               // whole particles up to the cap
  EXPECT_EQ(StartProbePoses(5, static_cast<int>(kStartProbeMaxQueries) * 2), 1u);  // at least one
}

TEST(StartProbeTest, TheDelibotProbeIsDeterministicAndDrawnApartFromTheParticles) {
  const Office office;
  MonteCarloLocalizer mcl = office.Localizer(RayCastMethod::kDda);
  mcl.InitializeUniform();
  omp_set_num_threads(1);
  const KernelRecord one = office.Probe(mcl, RayCastMethod::kDda, 150);
  omp_set_num_threads(2);
  const KernelRecord two = office.Probe(mcl, RayCastMethod::kDda, 150);
  const int per_pose = office.beams.Count(office.geometry.beam_count);
  ASSERT_EQ(one.query_count(), 150u * per_pose);
  EXPECT_EQ(one.fetch_offsets, two.fetch_offsets);
  EXPECT_EQ(one.last_exits, two.last_exits);
  EXPECT_EQ(one.fetch_addresses, two.fetch_addresses);
  // The same distribution as the particles (the initial stream reproduces
  // them), but a stream of its own: the probe never casts their rays.
  int same_as_particle = 0, probe_same_as_particle = 0;
  for (std::size_t i = 0; i < mcl.particles().size(); ++i) {
    RandomStream initial(3, StreamPurpose::kInitialization, 0, i), probe(3, StreamPurpose::kStartProbe, 0, i);
    const Pose2 a = mcl.DrawInitialPose(initial), b = mcl.DrawInitialPose(probe);
    same_as_particle += a.x == mcl.particles()[i].x && a.y == mcl.particles()[i].y;
    probe_same_as_particle += b.x == mcl.particles()[i].x && b.y == mcl.particles()[i].y;
  }
  EXPECT_EQ(same_as_particle, static_cast<int>(mcl.particles().size()));
  EXPECT_EQ(probe_same_as_particle, 0);
}

TEST(StartProbeTest, TrackingProbesAroundTheStartPose) {
  const Office office;
  MonteCarloLocalizer mcl = office.Localizer(RayCastMethod::kRayMarching);
  const std::vector<std::uint32_t> free_cells = office.grid.FreeCellIndices();
  const std::uint32_t cell = free_cells[free_cells.size() / 2];
  const double r = office.grid.resolution_m();
  const Pose2 start{(cell / office.grid.size_y() + 0.5) * r, (cell % office.grid.size_y() + 0.5) * r, 0.4};
  mcl.InitializeAround(start, 0.05, 0.02);
  for (std::size_t i = 0; i < 100; ++i) {
    RandomStream stream(3, StreamPurpose::kStartProbe, 0, i);
    const Pose2 p = mcl.DrawInitialPose(stream);
    EXPECT_LT(std::hypot(p.x - start.x, p.y - start.y), 0.3) << i;  // 6 sigma
    EXPECT_LT(std::abs(WrapAngle(p.theta - start.theta)), 0.12) << i;
  }
}

}  // namespace
}  // namespace rc
