// The defaults `rcbench delibot` starts from (delibot_defaults.h,
// docs/defaults.md): the staged sensor model hands over from the global
// model to the tracking model once one hypothesis is left, the dense first
// set is sized by the map, the defaults fit the options a user gives, and
// the built-in demo converges early and claims only what holds.
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>

#include "delibot/same_rows.h"
#include "maps/office_map_generator.h"
#include "support/simd_levels.h"
#include "synthetic_world.h"
#include "workloads/delibot/delibot_defaults.h"
#include "workloads/delibot/monte_carlo_localizer.h"
#include "workloads/delibot/staged_sensor_model.h"
#include "workloads/delibot/trace_simulator.h"

namespace rc {
namespace {

// Scores every particle with a fixed value and counts its calls.
class TaggedModel final : public SensorModel {
 public:
  explicit TaggedModel(double tag) : tag_(tag) {}
  std::string name() const override { return "tag" + std::to_string(static_cast<int>(-tag_)); }
  void LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan&, const LaserGeometry&, const BeamSelection&,
                      std::vector<double>& log_likelihoods, SensorUpdateWork&) override {
    ++calls;
    log_likelihoods.assign(particles.size(), tag_);
  }
  void SelectionLogLikelihoods(const std::vector<Pose2>& particles, const LaserScan&, const LaserGeometry&,
                               const BeamSelection&, std::vector<double>& log_likelihoods, SensorUpdateWork&) override {
    ++selection_calls;
    log_likelihoods.assign(particles.size(), 10.0 * tag_);
  }
  int calls = 0, selection_calls = 0;

 private:
  double tag_;
};

// A staged model over a global model tagged -1 and a tracking model tagged
// -2, with what each was asked: Select() and Weigh() give the first
// particle's score from the first set's cut and from an ordinary update.
struct TaggedStages {
  TaggedModel* global;
  TaggedModel* tracking;
  std::unique_ptr<StagedSensorModel> staged;

  explicit TaggedStages(FirstSetScoring first_set) {
    auto g = std::make_unique<TaggedModel>(-1.0);
    auto t = std::make_unique<TaggedModel>(-2.0);
    global = g.get();
    tracking = t.get();
    staged = std::make_unique<StagedSensorModel>(std::move(g), std::move(t), first_set);
  }
  double Select() { return Score(true); }
  double Weigh() { return Score(false); }
  // Each model's {update, selection} calls so far.
  void ExpectCalls(std::pair<int, int> of_global, std::pair<int, int> of_tracking) const {
    EXPECT_EQ(std::make_pair(global->calls, global->selection_calls), of_global);
    EXPECT_EQ(std::make_pair(tracking->calls, tracking->selection_calls), of_tracking);
  }

 private:
  double Score(bool selection) {
    const std::vector<Pose2> particles(3);
    std::vector<double> ll;
    SensorUpdateWork work;
    if (selection)
      staged->SelectionLogLikelihoods(particles, {}, {}, {}, ll, work);
    else
      staged->LogLikelihoods(particles, {}, {}, {}, ll, work);
    return ll[0];
  }
};

TEST(StagedSensorModelTest, TheGlobalModelScoresUntilTrackingBegins) {
  TaggedStages m(FirstSetScoring::kGlobal);
  EXPECT_EQ(m.staged->name(), "tag1-then-tag2");
  EXPECT_TRUE(m.staged->HasTrackingStage());
  EXPECT_EQ(m.Select(), -10.0);
  EXPECT_EQ(m.Weigh(), -1.0);
  EXPECT_FALSE(m.staged->Tracking());
  m.staged->BeginTracking();
  EXPECT_TRUE(m.staged->Tracking());
  EXPECT_EQ(m.Weigh(), -2.0);
  // The dense first set is a global choice, before tracking or after.
  EXPECT_EQ(m.Select(), -10.0);
  m.ExpectCalls({1, 2}, {1, 0});
  EXPECT_THROW(StagedSensorModel(nullptr, std::make_unique<TaggedModel>(-1.0)), std::invalid_argument);
}

TEST(StagedSensorModelTest, TrackingFirstSetScoringSelectsWithTheTrackingModelOnly) {
  TaggedStages m(FirstSetScoring::kTracking);
  EXPECT_EQ(m.Select(), -20.0);
  // The later updates still weigh with the global model until tracking begins.
  EXPECT_EQ(m.Weigh(), -1.0);
  m.ExpectCalls({1, 0}, {0, 1});
  EXPECT_EQ(ParseFirstSetScoring("global"), FirstSetScoring::kGlobal);
  EXPECT_EQ(ParseFirstSetScoring(ToString(FirstSetScoring::kTracking)), FirstSetScoring::kTracking);
  EXPECT_THROW(ParseFirstSetScoring("beam"), std::invalid_argument);
}

// Gives the first set's particles the listed selection scores.
class ListedModel final : public SensorModel {
 public:
  explicit ListedModel(std::vector<double> scores) : scores_(std::move(scores)) {}
  std::string name() const override { return "listed"; }
  void LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan&, const LaserGeometry&, const BeamSelection&,
                      std::vector<double>& log_likelihoods, SensorUpdateWork&) override {
    log_likelihoods.assign(particles.size(), 0.0);
  }
  void SelectionLogLikelihoods(const std::vector<Pose2>&, const LaserScan&, const LaserGeometry&, const BeamSelection&,
                               std::vector<double>& log_likelihoods, SensorUpdateWork&) override {
    log_likelihoods = scores_;
  }

 private:
  std::vector<double> scores_;
};

// The mixture cut's selection weights, normalized: the mean of the two
// models' normalized posteriors.
std::vector<double> MixtureWeights(std::vector<double> global, std::vector<double> tracking) {
  StagedSensorModel staged(std::make_unique<ListedModel>(std::move(global)),
                           std::make_unique<ListedModel>(std::move(tracking)), FirstSetScoring::kMixture);
  const std::vector<Pose2> particles(2);
  std::vector<double> ll;
  SensorUpdateWork work;
  staged.SelectionLogLikelihoods(particles, {}, {}, {}, ll, work);
  double sum = 0.0;
  for (double x : ll) sum += std::exp(x);
  for (double& x : ll) x = std::exp(x) / sum;
  return ll;
}

TEST(StagedSensorModelTest, MixtureFirstSetScoringDrawsHalfByEachModelsPosterior) {
  // Posteriors (1/4, 3/4) and (1/2, 1/2), whatever each model's scale.
  const std::vector<double> mixed = MixtureWeights({-700.0, -700.0 + std::log(3.0)}, {5.0, 5.0});
  EXPECT_NEAR(mixed[0], 0.375, 1e-12);
  EXPECT_NEAR(mixed[1], 0.625, 1e-12);
  // A place only one model favours keeps half of the draws.
  const std::vector<double> split = MixtureWeights({0.0, -1000.0}, {-1000.0, 0.0});
  EXPECT_NEAR(split[0], 0.5, 1e-12);
  EXPECT_NEAR(split[1], 0.5, 1e-12);
  // A model that rules every particle out leaves the other's posterior.
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> one = MixtureWeights({-inf, -inf}, {0.0, std::log(3.0)});
  EXPECT_NEAR(one[0], 0.25, 1e-12);
  EXPECT_NEAR(one[1], 0.75, 1e-12);
  EXPECT_EQ(ToString(ParseFirstSetScoring("mixture")), "mixture");
}

// Scores 0 near a live place and -1000 nats elsewhere (far outside any
// window), so the places alive are exactly the scripted ones.
class PlacesModel final : public SensorModel {
 public:
  std::vector<Pose2> live_places;
  int calls = 0;
  std::string name() const override { return "places"; }
  void LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan&, const LaserGeometry&, const BeamSelection&,
                      std::vector<double>& log_likelihoods, SensorUpdateWork&) override {
    ++calls;
    log_likelihoods.assign(particles.size(), -1000.0);
    for (std::size_t i = 0; i < particles.size(); ++i)
      for (const Pose2& place : live_places) {
        const double d = std::hypot(particles[i].x - place.x, particles[i].y - place.y);
        if (d < 0.5) log_likelihoods[i] = -d * d;
      }
  }
};

TEST(StagedHandOverTest, TrackingBeginsAfterTenUpdatesWithOneHypothesisAndCutsTheSet) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.15, 0.03, 21);
  MclOptions o;
  o.particle_count = 1000;
  o.initial_particle_count = 40000;
  o.hypothesis_floor = {250, 6.0};
  o.max_particle_count = 5000;
  o.alpha_slow = o.alpha_fast = 0.0;
  o.update_min_d_m = o.update_min_a_rad = 0.0;  // a sensor update on every record
  auto global = std::make_unique<PlacesModel>();
  auto tracking = std::make_unique<PlacesModel>();
  PlacesModel* global_model = global.get();
  PlacesModel* tracking_model = tracking.get();
  global_model->live_places = {{3.0, 2.0, 0.0}, {8.0, 6.0, 0.0}};
  tracking_model->live_places = {{3.0, 2.0, 0.0}};
  MonteCarloLocalizer mcl(g, std::make_unique<StagedSensorModel>(std::move(global), std::move(tracking)), o);
  mcl.InitializeUniform();
  const LaserScan still = run.trace.scans[0];  // no motion: the places stay put
  int began_at = -1;
  for (int k = 0; k < 20; ++k) {
    if (k == 3) global_model->live_places.resize(1);  // from update 3 one place is left
    const MclStepResult step = mcl.Update(still, run.trace.geometry, k);
    if (k >= 1 && k <= 2) {
      EXPECT_EQ(step.hypotheses_alive, 2) << "update " << k;
    }
    EXPECT_EQ(step.tracking, began_at >= 0) << "update " << k;
    if (step.began_tracking) {
      EXPECT_EQ(began_at, -1) << "tracking begins once";
      began_at = k;
      EXPECT_EQ(mcl.particles().size(), 1000u) << "the set is cut to --particles at the hand-over";
    }
  }
  // From update 3 the second place's particles trail by 1000 nats: one
  // hypothesis alive in updates 3-12, and the tenth of them hands over.
  EXPECT_EQ(began_at, 12);
  EXPECT_EQ(global_model->calls, 13);   // updates 0-12 (update 0 selects from the dense set)
  EXPECT_EQ(tracking_model->calls, 7);  // updates 13-19
}

TEST(StagedHandOverTest, TrackingFromAKnownPoseStartsInTheTrackingStage) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.15, 0.03, 21);
  auto global = std::make_unique<PlacesModel>();
  auto tracking = std::make_unique<PlacesModel>();
  PlacesModel* global_model = global.get();
  MclOptions o;
  o.particle_count = 200;
  MonteCarloLocalizer mcl(g, std::make_unique<StagedSensorModel>(std::move(global), std::move(tracking)), o);
  mcl.InitializeAround(run.truth[0], 0.1, 0.05);
  EXPECT_TRUE(mcl.Update(run.trace.scans[0], run.trace.geometry, 0).tracking);
  EXPECT_EQ(global_model->calls, 0);
}

TEST(InitialParticleCountTest, AutoLeavesFourParticlesNearAnyPose) {
  MclOptions o;
  o.initial_particle_count = kAutoInitialParticles;
  // 4 per (pi 0.15^2 m^2 x 6 deg) of the pose space: 3395.3 per m^2 of free space.
  const double per_m2 = 4.0 * 2.0 * M_PI / (M_PI * 0.15 * 0.15 * 2.0 * 3.0 * M_PI / 180.0);
  EXPECT_NEAR(per_m2, 3395.3, 0.1);
  EXPECT_EQ(InitialParticleCount(o, 483.0), static_cast<std::size_t>(std::ceil(per_m2 * 483.0)));
  EXPECT_EQ(InitialParticleCount(o, 0.1), 2000u) << "never fewer than the working set";
  EXPECT_EQ(InitialParticleCount(o, 1e6), static_cast<std::size_t>(kAutoInitialParticlesCap));
  o.initial_particle_count = 0;
  EXPECT_EQ(InitialParticleCount(o, 483.0), 2000u);
  o.initial_particle_count = 500000;
  EXPECT_EQ(InitialParticleCount(o, 483.0), 500000u);
  std::string error;
  EXPECT_TRUE(o.IsValid(&error));
  o.initial_particle_count = kAutoInitialParticles;
  EXPECT_TRUE(o.IsValid(&error)) << error;
  o.initial_particle_count = -2;
  EXPECT_FALSE(o.IsValid(&error));
}

TEST(DefaultSettingsTest, DefaultsFitTheOptionsAUserGives) {
  DelibotSettings s = DefaultDelibotSettings();
  EXPECT_EQ(s.sensor_model, SensorModelKind::kLikelihoodThenBeam);
  EXPECT_TRUE(s.audit_claims);
  std::string error;
  EXPECT_TRUE(s.mcl.IsValid(&error)) << error;
  // A small set: the floor follows it, so that it stays valid.
  s.mcl.particle_count = 300;
  EXPECT_EQ(FitDefaultsToGivenOptions(s, {}, false), "");
  EXPECT_EQ(s.mcl.hypothesis_floor.min_particles, 150);
  EXPECT_TRUE(s.mcl.IsValid(&error)) << error;
  // No floor asked for: the set cannot grow either.
  s = DefaultDelibotSettings();
  s.mcl.hypothesis_floor.min_particles = 0;
  GivenDelibotOptions given;
  given.hypothesis_floor = true;
  FitDefaultsToGivenOptions(s, given, false);
  EXPECT_EQ(s.mcl.max_particle_count, 0);
  EXPECT_TRUE(s.mcl.IsValid(&error)) << error;
  // A given floor above half the set is the user's, and is refused.
  s = DefaultDelibotSettings();
  s.mcl.particle_count = 300;
  FitDefaultsToGivenOptions(s, given, false);
  EXPECT_FALSE(s.mcl.IsValid(&error));
  // The beam model alone: claims unaudited, with a note, unless asked for.
  s = DefaultDelibotSettings();
  s.sensor_model = SensorModelKind::kBeam;
  EXPECT_NE(FitDefaultsToGivenOptions(s, {}, false).find("not audited"), std::string::npos);
  EXPECT_FALSE(s.audit_claims);
  s = DefaultDelibotSettings();
  s.sensor_model = SensorModelKind::kBeam;
  GivenDelibotOptions asked;
  asked.claim_audit = true;
  EXPECT_EQ(FitDefaultsToGivenOptions(s, asked, false), "");
  EXPECT_TRUE(s.audit_claims);
  // MRPT has none of our filter's extras, and no staged model.
  s = DefaultDelibotSettings();
  EXPECT_NE(FitDefaultsToGivenOptions(s, {}, true).find("beam"), std::string::npos);
  EXPECT_EQ(s.sensor_model, SensorModelKind::kBeam);
  EXPECT_EQ(s.mcl.initial_particle_count, 0);
  EXPECT_EQ(s.mcl.hypothesis_floor.min_particles, 0);
  EXPECT_EQ(s.mcl.max_particle_count, 0);
  EXPECT_FALSE(s.audit_claims);
  // ... but an audit asked for stays, for the engine to refuse.
  s = DefaultDelibotSettings();
  GivenDelibotOptions audit_given;
  audit_given.claim_audit = true;
  FitDefaultsToGivenOptions(s, audit_given, true);
  EXPECT_TRUE(s.audit_claims);
}

struct Demo {
  OccupancyGrid grid;
  SensorTrace trace;
  std::vector<Pose2> truth;
};

// The built-in demo's inputs (workloads/rcbench/demo_inputs.cc): the
// generated office map and 400 simulated records, seed 1.
Demo MakeDemo(int records) {
  Demo d;
  d.grid = GenerateOfficeMap(OfficeMapOptions{});
  SimulationOptions sim;
  sim.record_count = records;
  const SimulatedTrace simulated = SimulateTrace(d.grid, sim);
  d.trace = simulated.trace;
  for (const auto& p : simulated.ground_truth) d.truth.push_back(p.pose);
  return d;
}

// The README's first command (`rcbench delibot`, seed 1): converged within
// the first quarter of the records, the filter's own claim made there too,
// never withdrawn, its audit passed, and every record after it within 1 m
// of the truth; then tracked by the beam model, whose ray casts the
// backends price, to about a centimetre.
TEST(DefaultSettingsTest, TheDemoConvergesEarlyAndClaimsOnlyWhatHolds) {
  const Demo demo = MakeDemo(400);
  const DelibotResult r = RunDelibot(demo.grid, demo.trace, &demo.truth, DefaultDelibotSettings());
  const DelibotSummary& m = r.summary;
  EXPECT_FALSE(m.any_non_finite_weight);
  ASSERT_GE(m.convergence_iteration, 0);
  EXPECT_LT(m.convergence_iteration, 100);
  ASSERT_GE(m.self_convergence_iteration, 0);
  EXPECT_LT(m.self_convergence_iteration, 100);
  EXPECT_EQ(m.claims_withdrawn, 0);
  EXPECT_EQ(m.claims_refused, 0);
  long audits_passed = 0;
  for (const DelibotRow& row : r.rows) audits_passed += row.claim_audit == ClaimAuditOutcome::kPassed;
  EXPECT_EQ(audits_passed, 1);
  EXPECT_EQ(m.standing_claim_iteration, m.self_convergence_iteration);
  EXPECT_TRUE(m.converged);
  EXPECT_EQ(m.jumps_after_convergence, 0);
  for (const DelibotRow& row : r.rows)
    if (row.iteration >= m.self_convergence_iteration) {
      ASSERT_LT(row.err_xy_m, 1.0) << "record " << row.iteration;
    }
  EXPECT_LT(m.median_err_xy_m, 0.02);
  EXPECT_LT(m.final_err_xy_m, 0.05);
  // The beam model tracks: its updates cast rays (several nodes per ray;
  // the likelihood field's lookups count one node each).
  long ray_cast_updates = 0;
  for (const DelibotRow& row : r.rows) ray_cast_updates += row.sensor_updated && row.NodesPerRay() > 1.5;
  EXPECT_GT(ray_cast_updates, m.sensor_updates * 9 / 10);
}

TEST(DefaultSettingsTest, SameSeedSameTimelineAtAnyThreadCount) {
  const Demo demo = MakeDemo(40);
  DelibotSettings s = DefaultDelibotSettings();
  s.mcl.initial_particle_count = 100000;  // the auto 850,000 twice would take most of the time
  omp_set_num_threads(1);
  const DelibotResult one = RunDelibot(demo.grid, demo.trace, &demo.truth, s);
  omp_set_num_threads(2);
  const DelibotResult two = RunDelibot(demo.grid, demo.trace, &demo.truth, s);
  test::ExpectSameRows(one, two);
  bool tracked = false;
  for (const DelibotRow& row : one.rows) tracked = tracked || row.NodesPerRay() > 1.5;
  EXPECT_TRUE(tracked) << "both stages must be covered";
}

// Every SIMD path (scalar, AVX2, AVX-512 where the CPU runs them; rcbench
// --simd) gives the same timeline, priced cycles and energy included: the
// casts, the recording and the cost models' SIMD forms agree bit for bit.
TEST(DefaultSettingsTest, SameSeedSameTimelineOnEverySimdPath) {
  const Demo demo = MakeDemo(12);
  DelibotSettings s = DefaultDelibotSettings();
  s.mcl.initial_particle_count = 20000;
  s.price_backends = true;
  const DelibotResult widest = RunDelibot(demo.grid, demo.trace, &demo.truth, s);
  long priced = 0;
  for (const DelibotRow& row : widest.rows) priced += row.priced;
  EXPECT_GT(priced, 0) << "the beam model's updates must be priced";
  for (SimdLevel level : test::SimdLevelsThisCpuRuns()) {
    if (level == CpuSimdLevel()) continue;
    SCOPED_TRACE(std::string(ToString(level)));
    const test::ScopedSimdLimit limit(level);
    const DelibotResult other = RunDelibot(demo.grid, demo.trace, &demo.truth, s);
    test::ExpectSameRows(widest, other);
    ASSERT_EQ(widest.rows.size(), other.rows.size());
    for (std::size_t i = 0; i < widest.rows.size(); ++i) {
      const LedgerIteration& a = widest.rows[i].pricing;
      const LedgerIteration& b = other.rows[i].pricing;
      ASSERT_EQ(widest.rows[i].priced, other.rows[i].priced) << i;
      EXPECT_EQ(a.backend, b.backend) << i;
      EXPECT_EQ(a.chosen_cycles, b.chosen_cycles) << i;
      EXPECT_EQ(a.chosen_energy_j, b.chosen_energy_j) << i;
      ASSERT_EQ(a.costs.size(), b.costs.size()) << i;
      for (std::size_t k = 0; k < a.costs.size(); ++k) {
        EXPECT_EQ(a.costs[k].cycles, b.costs[k].cycles) << i << " " << a.costs[k].backend;
        EXPECT_EQ(a.costs[k].energy_joules, b.costs[k].energy_joules) << i << " " << a.costs[k].backend;
      }
    }
  }
}

}  // namespace
}  // namespace rc
