// OMPL's own style of nearest-neighbour test (ompl/tests/datastructures/
// nearestneighbors.cpp): random data, and every query of the structure under
// test must equal brute force (NearestNeighborsLinear), here exactly and with
// ties resolved deterministically, after adds, removes and clear, for both
// formulations and several k, r and dimensions.
#include <algorithm>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>

#include "nn_test_space.h"
#include "workloads/movebot/backend_nearest_neighbors.h"

namespace rc {
namespace {

using test::NnTestSpace;
using test::State;

struct Case {
  BallQueryFormulation formulation;
  unsigned dimension;
  double sphere_radius;
  bool early_exit;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << ToString(c.formulation) << ", n = " << c.dimension << ", sphere_radius = " << c.sphere_radius
      << (c.early_exit ? ", early exit" : ", no early exit");
}

std::string Name(const testing::TestParamInfo<Case>& info) {
  return std::string(ToString(info.param.formulation)) + "_n" + std::to_string(info.param.dimension) + "_r" +
         std::to_string(static_cast<int>(info.param.sphere_radius * 100)) + (info.param.early_exit ? "_exit" : "_full");
}

class NearestNeighborsVsLinear : public testing::TestWithParam<Case> {
 protected:
  NearestNeighborsVsLinear()
      : space_(GetParam().dimension),
        nn_(
            Config(), [](const State& s) { return static_cast<const double*>(NnTestSpace::Values(s)); },
            GetParam().dimension) {
    auto distance = [this](const State& a, const State& b) { return space_.Distance(a, b); };
    nn_.setDistanceFunction(distance);
    linear_.setDistanceFunction(distance);
  }

  static BallQueryConfig Config() {
    BallQueryConfig c;
    c.formulation = GetParam().formulation;
    c.sphere_radius = GetParam().sphere_radius;
    c.early_exit = GetParam().early_exit;
    c.record = GetParam().dimension <= kMaxRecordedDimension;
    return c;
  }

  void Add(State s) {
    nn_.add(s);
    linear_.add(s);
  }

  // Brute force with the documented tie rule: sorted by distance, the
  // element added first wins (a stable sort of Linear's insertion-ordered list).
  std::vector<State> Reference(State q) const {
    std::vector<State> all;
    linear_.list(all);
    std::stable_sort(all.begin(), all.end(),
                     [&](State a, State b) { return space_.Distance(a, q) < space_.Distance(b, q); });
    return all;
  }

  // Every query kind against brute force.
  void ExpectAllQueriesEqual(State q) {
    const std::vector<State> ref = Reference(q);
    ASSERT_EQ(nn_.size(), linear_.size());
    if (!ref.empty()) {
      EXPECT_EQ(nn_.nearest(q), linear_.nearest(q));  // Linear keeps the first of equals too
      EXPECT_EQ(nn_.nearest(q), ref.front());
    }
    for (std::size_t k : {std::size_t{1}, std::size_t{2}, std::size_t{5}, std::size_t{17}, ref.size() + 3}) {
      std::vector<State> got, lin;
      nn_.nearestK(q, k, got);
      linear_.nearestK(q, k, lin);
      const std::vector<State> want(ref.begin(), ref.begin() + std::min(k, ref.size()));
      EXPECT_EQ(got, want) << "k = " << k;
      ASSERT_EQ(got.size(), lin.size());
      for (std::size_t i = 0; i < got.size(); ++i)  // same distances as OMPL's own answer
        EXPECT_EQ(space_.Distance(got[i], q), space_.Distance(lin[i], q)) << "k = " << k << ", rank " << i;
    }
    for (double r : {0.0, 0.05, 0.2, 0.5, 1.5}) {
      std::vector<State> got, lin;
      nn_.nearestR(q, r, got);
      linear_.nearestR(q, r, lin);
      std::vector<State> want;
      for (State s : ref)
        if (space_.Distance(s, q) <= r) want.push_back(s);
      EXPECT_EQ(got, want) << "r = " << r;
      EXPECT_EQ(got.size(), lin.size()) << "r = " << r;
    }
  }

  NnTestSpace space_;
  BackendNearestNeighbors<State> nn_;
  ompl::NearestNeighborsLinear<State> linear_;
};

TEST_P(NearestNeighborsVsLinear, RandomDataAddRemoveClear) {
  std::mt19937_64 rng(1234 + GetParam().dimension);
  for (int i = 0; i < 300; ++i) Add(space_.Make(rng, -1, 1));
  for (int i = 0; i < 12; ++i) ExpectAllQueriesEqual(space_.Make(rng, -1.2, 1.2));

  // Remove a third, in random order; removing something absent fails on both.
  std::vector<State> all;
  linear_.list(all);
  std::shuffle(all.begin(), all.end(), rng);
  for (std::size_t i = 0; i < all.size() / 3; ++i) {
    EXPECT_TRUE(nn_.remove(all[i]));
    EXPECT_TRUE(linear_.remove(all[i]));
  }
  EXPECT_FALSE(nn_.remove(all[0]));
  std::vector<State> listed, listed_linear;
  nn_.list(listed);
  linear_.list(listed_linear);
  EXPECT_EQ(listed, listed_linear);
  for (int i = 0; i < 8; ++i) ExpectAllQueriesEqual(space_.Make(rng, -1.2, 1.2));

  // Grow again past the rebuild threshold, then clear and start over.
  for (int i = 0; i < 400; ++i) Add(space_.Make(rng, -1, 1));
  for (int i = 0; i < 8; ++i) ExpectAllQueriesEqual(space_.Make(rng, -1.2, 1.2));
  nn_.clear();
  linear_.clear();
  EXPECT_EQ(nn_.size(), 0u);
  std::vector<State> none;
  nn_.nearestK(space_.Make(rng, -1, 1), 3, none);
  EXPECT_TRUE(none.empty());
  EXPECT_THROW(nn_.nearest(space_.Make(rng, -1, 1)), ompl::Exception);
  for (int i = 0; i < 50; ++i) Add(space_.Make(rng, -1, 1));
  for (int i = 0; i < 6; ++i) ExpectAllQueriesEqual(space_.Make(rng, -1.2, 1.2));
}

TEST_P(NearestNeighborsVsLinear, TiesOnAGridAndDuplicates) {
  std::mt19937_64 rng(99 + GetParam().dimension);
  // Coordinates on a 0.25 grid: many states at equal distances, and duplicates.
  for (int i = 0; i < 200; ++i) Add(space_.Make(rng, -1, 1, 0.25));
  State dup = space_.Make(rng, -1, 1, 0.25);
  for (int i = 0; i < 3; ++i) Add(dup);  // the same element three times
  for (int i = 0; i < 10; ++i) ExpectAllQueriesEqual(space_.Make(rng, -1, 1, 0.25));
  ExpectAllQueriesEqual(dup);  // a query at distance 0 from three entries
  EXPECT_TRUE(nn_.remove(dup));
  EXPECT_TRUE(linear_.remove(dup));
  ExpectAllQueriesEqual(dup);
}

TEST_P(NearestNeighborsVsLinear, IncrementalLikeRrtStar) {
  // RRT*'s pattern: query, then add; small trees included (one state, two).
  std::mt19937_64 rng(7 + GetParam().dimension);
  for (int i = 0; i < 150; ++i) {
    State q = space_.Make(rng, -1, 1);
    if (i % 10 == 0 || i < 4) ExpectAllQueriesEqual(q);
    Add(q);
  }
}

INSTANTIATE_TEST_SUITE_P(BothFormulations, NearestNeighborsVsLinear,
                         testing::Values(Case{BallQueryFormulation::kPSphere, 5, 0.3, true},
                                         Case{BallQueryFormulation::kPRay, 5, 0.3, true},
                                         Case{BallQueryFormulation::kPSphere, 5, 0.3, false},
                                         Case{BallQueryFormulation::kPRay, 5, 0.3, false},
                                         Case{BallQueryFormulation::kPSphere, 2, 0.05, true},
                                         Case{BallQueryFormulation::kPRay, 3, 2.0, true},
                                         Case{BallQueryFormulation::kPSphere, 1, 0.1, true},
                                         Case{BallQueryFormulation::kPRay, 8, 0.7, true},
                                         Case{BallQueryFormulation::kPSphere, 8, 0.7, false}),
                         Name);

TEST(BackendNearestNeighbors, RejectsADistanceThatIsNotEuclidean) {
  NnTestSpace space(3);
  BackendNearestNeighbors<State> nn(
      BallQueryConfig{}, [](const State& s) { return static_cast<const double*>(NnTestSpace::Values(s)); }, 3);
  nn.setDistanceFunction([](const State& a, const State& b) {  // L1: not what the kernel computes
    double d = 0;
    for (int i = 0; i < 3; ++i) d += std::abs(NnTestSpace::Values(a)[i] - NnTestSpace::Values(b)[i]);
    return d;
  });
  std::mt19937_64 rng(5);
  nn.add(space.Make(rng, 0, 1));
  try {
    nn.add(space.Make(rng, 0, 1));
    FAIL() << "an L1 distance function was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("RealVectorStateSpace"), std::string::npos) << e.what();
  }
}

TEST(BackendNearestNeighbors, BadConfigurationIsAClearError) {
  auto coords = [](const State& s) { return static_cast<const double*>(NnTestSpace::Values(s)); };
  auto expect_error = [&](BallQueryConfig c, std::size_t n, const std::string& field) {
    try {
      BackendNearestNeighbors<State> nn(c, coords, n);
      FAIL() << "accepted a bad " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  BallQueryConfig c;
  c.sphere_radius = 0;
  expect_error(c, 5, "sphere_radius");
  c.sphere_radius = std::nan("");
  expect_error(c, 5, "sphere_radius");
  c = BallQueryConfig{};
  c.radius_growth = 1.0;
  expect_error(c, 5, "radius_growth");
  c = BallQueryConfig{};
  c.formulation = static_cast<BallQueryFormulation>(7);
  expect_error(c, 5, "formulation");
  expect_error(BallQueryConfig{}, 0, "dimension");
  expect_error(BallQueryConfig{}, 7, "at most 6 coordinates");
  EXPECT_THROW(BackendNearestNeighbors<State>(BallQueryConfig{}, nullptr, 5), std::invalid_argument);
  EXPECT_THROW(ParseBallQueryFormulation("ray"), std::invalid_argument);
  EXPECT_EQ(ParseBallQueryFormulation("P-Sphere"), BallQueryFormulation::kPSphere);
  EXPECT_EQ(ParseBallQueryFormulation("pray"), BallQueryFormulation::kPRay);
}

TEST(BackendNearestNeighbors, RejectsANonFiniteCoordinate) {
  NnTestSpace space(2);
  BackendNearestNeighbors<State> nn(
      BallQueryConfig{}, [](const State& s) { return static_cast<const double*>(NnTestSpace::Values(s)); }, 2);
  std::mt19937_64 rng(3);
  State s = space.Make(rng, 0, 1);
  NnTestSpace::Values(s)[1] = std::nan("");
  EXPECT_THROW(nn.add(s), std::invalid_argument);
  EXPECT_EQ(nn.size(), 0u);
}

}  // namespace
}  // namespace rc
