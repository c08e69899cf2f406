// The particle set grows while rivals are alive (MclOptions::
// max_particle_count): every live hypothesis gets room for its floor, up to
// the cap, and the set shrinks back to particle_count once one hypothesis is
// left. A scripted sensor model makes the places and their evidence exact.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "synthetic_world.h"
#include "workloads/delibot/mcl_options.h"
#include "workloads/delibot/monte_carlo_localizer.h"

namespace rc {
namespace {

// Scores a pose 0 at the centre of a live place, falling off as -d^2 within
// 0.5 m of it (so that weights differ and every update resamples), and
// -1000 nats anywhere else: far outside any hypothesis window.
class PlacesModel final : public SensorModel {
 public:
  std::vector<Pose2> live_places;
  std::string name() const override { return "places"; }
  void LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan&, const LaserGeometry&, const BeamSelection&,
                      std::vector<double>& log_likelihoods, SensorUpdateWork&) override {
    log_likelihoods.assign(particles.size(), -1000.0);
    for (std::size_t i = 0; i < particles.size(); ++i)
      for (const Pose2& place : live_places) {
        const double d = std::hypot(particles[i].x - place.x, particles[i].y - place.y);
        if (d < 0.5) log_likelihoods[i] = -d * d;
      }
  }
};

struct GrowthRun {
  std::vector<std::size_t> sizes;  // particles after each update
  std::vector<int> alive;          // hypotheses alive at each update
};

// Updates 0-2 see three places alive, updates 3-5 only the first.
GrowthRun RunThreeThenOnePlace(int max_particle_count) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.15, 0.03, 21);
  MclOptions o;
  o.particle_count = 1000;
  o.initial_particle_count = 40000;
  o.hypothesis_floor = {250, 200.0};
  o.max_particle_count = max_particle_count;
  o.alpha_slow = o.alpha_fast = 0.0;
  o.resample_ess_fraction = 1.0;
  o.update_min_d_m = o.update_min_a_rad = 0.0;  // a sensor update on every record
  auto owned = std::make_unique<PlacesModel>();
  PlacesModel* model = owned.get();
  // Three places in free space of the room, far enough apart to be three
  // clusters (1 m bins).
  model->live_places = {{3.0, 2.0, 0.0}, {8.0, 6.0, 0.0}, {2.0, 6.5, 0.0}};
  MonteCarloLocalizer mcl(g, std::move(owned), o);
  mcl.InitializeUniform();
  LaserScan still = run.trace.scans[0];  // the same odometry every time: no motion
  GrowthRun out;
  for (int k = 0; k < 6; ++k) {
    if (k == 3) model->live_places.resize(1);
    const MclStepResult step = mcl.Update(still, run.trace.geometry, k);
    out.sizes.push_back(mcl.particles().size());
    out.alive.push_back(step.hypotheses_alive);
  }
  return out;
}

TEST(ParticleSetGrowthTest, EveryLiveHypothesisGetsRoomForItsFloorThenTheSetShrinks) {
  const GrowthRun r = RunThreeThenOnePlace(5000);
  // The dense first set is not clustered: it keeps as many as allowed.
  EXPECT_EQ(r.alive[0], 0);
  EXPECT_EQ(r.sizes[0], 5000u);
  // Three places alive: twice the 250-particle floor each.
  for (int k = 1; k <= 2; ++k) {
    EXPECT_EQ(r.alive[k], 3) << "update " << k;
    EXPECT_EQ(r.sizes[k], 1500u) << "update " << k;
  }
  // Two places fall 1000 nats behind: one hypothesis, the working size.
  // (Update 3 still sees the particles of all three places.)
  EXPECT_EQ(r.alive[3], 1);
  for (int k = 3; k <= 5; ++k) EXPECT_EQ(r.sizes[k], 1000u) << "update " << k;
}

TEST(ParticleSetGrowthTest, TheCapBoundsTheSet) {
  const GrowthRun r = RunThreeThenOnePlace(1200);
  EXPECT_EQ(r.sizes[0], 1200u);
  EXPECT_EQ(r.alive[1], 3);
  EXPECT_EQ(r.sizes[1], 1200u);
  EXPECT_EQ(r.sizes[5], 1000u);
}

TEST(ParticleSetGrowthTest, WithoutACapTheSetKeepsItsSize) {
  const GrowthRun r = RunThreeThenOnePlace(0);
  EXPECT_EQ(r.alive[1], 3);
  for (std::size_t size : r.sizes) EXPECT_EQ(size, 1000u);
}

TEST(ParticleSetGrowthTest, OptionsBoundTheCap) {
  MclOptions o;
  std::string error;
  o.hypothesis_floor.min_particles = 100;
  o.max_particle_count = o.particle_count - 1;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("max particles"), std::string::npos);
  o.max_particle_count = 10000001;
  EXPECT_FALSE(o.IsValid(&error));
  o.max_particle_count = 20000;
  EXPECT_TRUE(o.IsValid(&error)) << error;
  // A cap without a floor would do nothing: refused, not ignored.
  o.hypothesis_floor.min_particles = 0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("hypothesis floor"), std::string::npos);
}

}  // namespace
}  // namespace rc
