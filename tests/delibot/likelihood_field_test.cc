// The likelihood field must score a beam by the distance from its end point
// to the wall's face, in the map frame of occupancy_grid.h (origin at the
// outer corner of cell (0, 0), cell centres at (i + 0.5) * r). A lookup of
// the centre-to-centre distance at the end point's cell is off by half a
// cell, and the filter then tracks half a cell behind the truth. Inside a
// wall it scores the depth below the face (signed), unless asked for AMCL's
// unsigned field.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "workloads/delibot/likelihood_field_model.h"

namespace rc {
namespace {

constexpr double kResolution = 0.1;

// 4 m x 4 m, free for x < 2 m, `state` from x = 2 m on.
OccupancyGrid HalfFilled(CellState state) {
  OccupancyGrid g(40, 40, kResolution);
  for (int ix = 20; ix < 40; ++ix)
    for (int iy = 0; iy < 40; ++iy) g.Set(ix, iy, state);
  return g;
}

// A solid wall from x = 2 m on.
OccupancyGrid HalfWall() { return HalfFilled(CellState::kOccupied); }

TEST(LikelihoodFieldTest, DistanceIsMeasuredToTheWallFace) {
  const OccupancyGrid g = HalfWall();
  const LikelihoodFieldModel model(g, LikelihoodFieldParams{});
  // Every point in front of the wall, including points inside one cell
  // (where a per-cell lookup is constant), measures its true distance.
  for (double x = 1.0; x <= 2.0 + 1e-9; x += 0.01) {
    for (double y : {1.0, 1.05, 1.333}) {
      EXPECT_NEAR(model.DistanceAt(x, y), 2.0 - x, 1e-6) << "x " << x << " y " << y;
    }
  }
}

// Inside a wall the signed field measures the depth below the face; AMCL's
// unsigned field is 0 there, so pushing an end point through a wall is free.
TEST(LikelihoodFieldTest, InsideAWallTheDistanceIsTheDepthUnlessUnsigned) {
  const OccupancyGrid g = HalfWall();
  LikelihoodFieldParams signed_params;
  signed_params.signed_distance = true;
  const LikelihoodFieldModel signed_model(g, signed_params);
  const LikelihoodFieldModel unsigned_model(g, LikelihoodFieldParams{});
  for (double x = 2.0; x <= 3.0 + 1e-9; x += 0.01) {
    for (double y : {1.0, 1.05, 1.333}) {
      EXPECT_NEAR(signed_model.DistanceAt(x, y), x - 2.0, 1e-6) << "x " << x << " y " << y;
      EXPECT_NEAR(unsigned_model.DistanceAt(x, y), 0.0, 1e-6) << "x " << x << " y " << y;
    }
  }
  // Deeper than the cap: the cap, as in front of the wall.
  EXPECT_DOUBLE_EQ(signed_model.DistanceAt(3.95, 1.0), 1.95);
  LikelihoodFieldParams capped = signed_params;
  capped.max_occ_dist_m = 0.5;
  EXPECT_DOUBLE_EQ(LikelihoodFieldModel(g, capped).DistanceAt(3.0, 1.0), 0.5);
  // A map made only of walls: no free cell to measure depth to, so the cap.
  OccupancyGrid solid(10, 10, kResolution);
  for (int ix = 0; ix < 10; ++ix)
    for (int iy = 0; iy < 10; ++iy) solid.Set(ix, iy, CellState::kOccupied);
  EXPECT_DOUBLE_EQ(LikelihoodFieldModel(solid, capped).DistanceAt(0.55, 0.55), 0.5);
}

// The ray casters and `rcbench simulate` stop a ray at an unknown cell, so a
// simulated beam ends on the edge of mapped free space. By default that end
// point is a miss (the cap); with unknown_is_edge it is a hit on a surface,
// and deeper in the unknown space it scores by its depth below the edge.
TEST(LikelihoodFieldTest, UnknownSpaceIsAMissOrAnEdgeSurface) {
  const OccupancyGrid g = HalfFilled(CellState::kUnknown);  // unmapped from x = 2 m on
  LikelihoodFieldParams miss, edge;
  edge.unknown_is_edge = true;
  const LikelihoodFieldModel miss_model(g, miss), edge_model(g, edge);
  for (double x = 1.3; x < 2.0; x += 0.05) {
    EXPECT_NEAR(edge_model.DistanceAt(x, 2.0), 2.0 - x, 1e-6) << "x " << x;
    // Measured to occupied cells only, and there are none.
    EXPECT_DOUBLE_EQ(miss_model.DistanceAt(x, 2.0), miss.max_occ_dist_m) << "x " << x;
  }
  for (double x = 2.0; x <= 3.5; x += 0.05) {
    EXPECT_NEAR(edge_model.DistanceAt(x, 2.0), x - 2.0, 1e-6) << "x " << x;
    EXPECT_DOUBLE_EQ(miss_model.DistanceAt(x, 2.0), miss.max_occ_dist_m) << "x " << x;
  }
}

TEST(LikelihoodFieldTest, DistanceIsCappedAndOutsideTheMapIsFar) {
  const OccupancyGrid g = HalfWall();
  LikelihoodFieldParams p;
  p.max_occ_dist_m = 0.5;
  const LikelihoodFieldModel model(g, p);
  EXPECT_DOUBLE_EQ(model.DistanceAt(0.2, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(model.DistanceAt(-0.01, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(model.DistanceAt(1.0, 4.0), 0.5);
  // A map without any occupied cell: every distance is the cap, not NaN.
  const OccupancyGrid empty(10, 10, kResolution);
  const LikelihoodFieldModel empty_model(empty, p);
  EXPECT_DOUBLE_EQ(empty_model.DistanceAt(0.55, 0.55), 0.5);
}

// A noise-free scan of a wall scores best at the pose it was taken from, not
// half a cell closer to the wall (where a cell-centre lookup peaks: it moves
// the end points inside the wall cells).
TEST(LikelihoodFieldTest, ExactScanOfAWallScoresBestAtItsOwnPose) {
  const OccupancyGrid g = HalfWall();
  LaserGeometry geometry;
  geometry.max_range_m = 3.0;
  for (bool signed_distance : {false, true}) {
    LikelihoodFieldParams p;
    p.sigma_hit_m = 0.05;  // sharp enough that a 1 cm shift changes the score
    p.max_range_m = geometry.max_range_m;
    p.signed_distance = signed_distance;
    LikelihoodFieldModel model(g, p);
    for (const Pose2& truth : {Pose2{1.03, 2.01, 0.0}, Pose2{1.27, 1.55, 0.4}, Pose2{0.86, 2.3, -0.3}}) {
      // Beams that meet the wall face x = 2 m within range; the others read
      // "no return" and the likelihood field skips them.
      LaserScan scan;
      const Pose2 sensor = SensorPose(truth, geometry);
      for (int i = 0; i < geometry.beam_count; ++i) {
        const double a = sensor.theta + geometry.BeamAngle(i);
        const double range = std::cos(a) > 0 ? (2.0 - sensor.x) / std::cos(a) : geometry.max_range_m;
        scan.ranges_m.push_back(static_cast<float>(std::min(range, geometry.max_range_m)));
      }
      std::vector<Pose2> candidates;
      for (int k = -10; k <= 10; ++k) candidates.push_back({truth.x + 0.01 * k, truth.y, truth.theta});
      std::vector<double> log_likelihoods;
      SensorUpdateWork work;
      model.LogLikelihoods(candidates, scan, geometry, BeamSelection{1}, log_likelihoods, work);
      // Index 10 is the truth. Approaching the wall from 10 cm in front, the
      // score rises with every centimetre (a per-cell lookup is flat over
      // each cell); past the truth the end points are inside the wall, where
      // the signed field makes the score fall again and AMCL's unsigned one
      // (distance 0) leaves it level: the flat side that biases AMCL forward.
      for (int k = 1; k <= 10; ++k)
        EXPECT_GT(log_likelihoods[k], log_likelihoods[k - 1]) << "shift " << 0.01 * (k - 10) << " m";
      for (int k = 11; k <= 20; ++k) {
        if (signed_distance) {
          EXPECT_LT(log_likelihoods[k], log_likelihoods[k - 1]) << "shift " << 0.01 * (k - 10) << " m";
        } else {
          EXPECT_LE(log_likelihoods[k], log_likelihoods[10] + 1e-9) << "shift " << 0.01 * (k - 10) << " m";
        }
      }
    }
  }
}

// nav2 AMCL's combination, worked by hand: each beam contributes pz^3 with
// pz = z_hit exp(-d^2 / 2 sigma^2) + z_rand / max_range, and the scan's
// likelihood is 1 + their sum, so it is bounded by 1 + n pz_max^3 however
// well the scan fits. The product instead gains a constant per beam.
TEST(LikelihoodFieldTest, AmclCubeSumMatchesItsFormula) {
  const OccupancyGrid g = HalfWall();
  LaserGeometry geometry;
  geometry.max_range_m = 3.0;
  LikelihoodFieldParams p;
  p.max_range_m = geometry.max_range_m;
  p.combination = BeamCombination::kAmclCubeSum;
  LikelihoodFieldModel cube(g, p);
  // Facing the wall: the sensor (0.25 m ahead of the robot) sits 0.5 m in
  // front of the face x = 2 m.
  const Pose2 pose{1.25, 2.0, 0.0};
  const Pose2 sensor = SensorPose(pose, geometry);
  ASSERT_NEAR(sensor.x, 1.5, 1e-12);
  // Scan 1: every beam within 72 deg of straight ahead ends on the face
  // (inside the map: |y - 2| <= 0.5 tan 72 deg = 1.54 m); the rest read "no
  // return", which the likelihood field skips.
  LaserScan on_face;
  int n_on_face = 0;
  for (int i = 0; i < geometry.beam_count; ++i) {
    const double c = std::cos(geometry.BeamAngle(i));
    const bool on = c > 0.3;
    on_face.ranges_m.push_back(static_cast<float>(on ? 0.5 / c : geometry.max_range_m));
    n_on_face += on;
  }
  ASSERT_GT(n_on_face, 100);
  // Scan 2: one beam, the first (pointing along -y), ending at (1.5, 1.5) m,
  // 0.5 m in front of the face.
  LaserScan one_beam;
  one_beam.ranges_m.assign(static_cast<std::size_t>(geometry.beam_count), static_cast<float>(geometry.max_range_m));
  one_beam.ranges_m[0] = 0.5f;
  std::vector<double> log_likelihoods;
  SensorUpdateWork work;
  const std::vector<Pose2> particles{pose};
  const double floor = p.z_rand / p.max_range_m;
  cube.LogLikelihoods(particles, on_face, geometry, BeamSelection{1}, log_likelihoods, work);
  // float ranges put the end points up to ~1e-7 m off the face
  EXPECT_NEAR(log_likelihoods[0], std::log(1.0 + n_on_face * std::pow(p.z_hit + floor, 3)), 1e-6);
  cube.LogLikelihoods(particles, one_beam, geometry, BeamSelection{1}, log_likelihoods, work);
  const double pz = p.z_hit * std::exp(-0.5 * std::pow(0.5 / p.sigma_hit_m, 2)) + floor;
  EXPECT_NEAR(log_likelihoods[0], std::log(1.0 + std::pow(pz, 3)), 1e-6);
  // The product of the same on-face beams: n log(z_hit / (sigma sqrt(2 pi)) + floor).
  p.combination = BeamCombination::kProduct;
  LikelihoodFieldModel product(g, p);
  product.LogLikelihoods(particles, on_face, geometry, BeamSelection{1}, log_likelihoods, work);
  EXPECT_NEAR(log_likelihoods[0], n_on_face * std::log(p.z_hit / (p.sigma_hit_m * std::sqrt(2 * M_PI)) + floor), 1e-4);

  // Cutting a dense initial set down, the cube-sum model scores as the product.
  cube.SelectionLogLikelihoods(particles, on_face, geometry, BeamSelection{1}, log_likelihoods, work);
  EXPECT_NEAR(log_likelihoods[0], n_on_face * std::log(p.z_hit / (p.sigma_hit_m * std::sqrt(2 * M_PI)) + floor), 1e-4);

  EXPECT_EQ(ParseBeamCombination("amcl-cube"), BeamCombination::kAmclCubeSum);
  EXPECT_EQ(ParseBeamCombination("product"), BeamCombination::kProduct);
  EXPECT_STREQ(ToString(BeamCombination::kAmclCubeSum), "amcl-cube");
  EXPECT_THROW(ParseBeamCombination("cube"), std::invalid_argument);
}

}  // namespace
}  // namespace rc
