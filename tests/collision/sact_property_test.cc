// Property tests of the staged SACT against the exact reference: 10^6
// random pairs (half of them built at or near exact contact), in double and
// float, with the error bands of sact.h as the pass criterion; the
// artifact's row/column bug must fail the same test. A sanitizer build
// scores a tenth of the pairs (a quarter in the 100,000-pair tests;
// tests/support/sanitizer_build.h).
//
// Truth per pair: a certificate when one exists (a separating axis checked
// on all 16 corners, or a common point strictly inside both boxes), else
// the LP reference, which also gives the signed depth s* that places a
// disagreement in or outside the band.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include "overlap_oracle.h"
#include "pair_generator.h"
#include "support/sanitizer_build.h"

namespace rc::test {
namespace {

constexpr std::uint64_t kPairs = FullOrUnderSanitizer<std::uint64_t>(1'000'000, 100'000);
constexpr std::uint64_t kSmallRunPairs = FullOrUnderSanitizer<std::uint64_t>(100'000, 25'000);
constexpr std::uint64_t kSeed = 20260;
constexpr long double kEps = 1e-6L;  // SactOptions default
constexpr long double kDoubleUlp = std::numeric_limits<double>::epsilon() / 2;
constexpr long double kFloatUlp = std::numeric_limits<float>::epsilon() / 2;

// Scales of a pair: S = sum of the six half extents (the epsilon band
// scales with it), M = max(S, largest centre coordinate) (rounding scales
// with it).
long double SizeScale(const ObbAabbPair& p) { return p.obb.half.sum() + p.box.half.sum(); }
long double MagnitudeScale(const ObbAabbPair& p) {
  return std::max<long double>({SizeScale(p), p.obb.centre.cwiseAbs().maxCoeff(), p.box.centre.cwiseAbs().maxCoeff()});
}

// The bands of sact.h. A false overlap must be the epsilon's doing (every
// axis within the epsilon's widening of the radii, EpsilonExplains) or
// rounding; a false separation can only be rounding (s* <= ulps x u x M).
struct Band {
  long double ulps;
  long double unit_roundoff;  // u
  long double epsilon;
  bool Allows(bool claimed_overlap, long double depth, const ObbAabbPair& p) const {
    const long double rounding = ulps * unit_roundoff * MagnitudeScale(p);
    if (!claimed_overlap) return depth <= rounding;
    return -depth <= rounding || EpsilonExplains(p.obb, p.box, epsilon, rounding);
  }
};
constexpr Band kDoubleBand{64, kDoubleUlp, kEps};
constexpr Band kFloatBand{8, kFloatUlp, kEps};

struct Stats {
  std::uint64_t pairs = 0, lp = 0, axis_certificates = 0, point_certificates = 0;
  std::uint64_t false_overlaps = 0, false_separations = 0, outside_band = 0;
  long double max_false_overlap_per_s = 0;  // max |s*| / S over false overlaps
  long double max_false_overlap_per_m = 0;  // max |s*| / M over false overlaps
  long double max_false_separation_per_m = 0;
  std::array<std::uint64_t, kPairFamilyCount> family_pairs{}, family_disagreements{};
  std::uint64_t touching_false_separations = 0;  // constructed gap == 0, claimed apart

  void Merge(const Stats& o) {
    pairs += o.pairs, lp += o.lp, axis_certificates += o.axis_certificates;
    point_certificates += o.point_certificates, false_overlaps += o.false_overlaps;
    false_separations += o.false_separations, outside_band += o.outside_band;
    max_false_overlap_per_s = std::max(max_false_overlap_per_s, o.max_false_overlap_per_s);
    max_false_overlap_per_m = std::max(max_false_overlap_per_m, o.max_false_overlap_per_m);
    max_false_separation_per_m = std::max(max_false_separation_per_m, o.max_false_separation_per_m);
    touching_false_separations += o.touching_false_separations;
    for (int f = 0; f < kPairFamilyCount; ++f)
      family_pairs[f] += o.family_pairs[f], family_disagreements[f] += o.family_disagreements[f];
  }
  void Print(const char* title) const {
    std::printf("[ %s ] %llu pairs; truth from %llu axis certificates, %llu point certificates, %llu LPs\n", title,
                (unsigned long long)pairs, (unsigned long long)axis_certificates,
                (unsigned long long)point_certificates, (unsigned long long)lp);
    std::printf(
        "    disagreements: %llu false overlaps (max |s*| = %.3Lg S = %.3Lg M), %llu false separations "
        "(max s* = %.3Lg M); outside the band: %llu\n",
        (unsigned long long)false_overlaps, max_false_overlap_per_s, max_false_overlap_per_m,
        (unsigned long long)false_separations, max_false_separation_per_m, (unsigned long long)outside_band);
    for (int f = 0; f < kPairFamilyCount; ++f)
      std::printf("    %-15s %8llu pairs, %7llu disagreements\n", ToString(static_cast<PairFamily>(f)),
                  (unsigned long long)family_pairs[f], (unsigned long long)family_disagreements[f]);
  }
};

// Records one claim against the truth (the LP is run for s* on a disagreement).
void Score(const ObbAabbPair& p, const SactResult& claim, Truth& truth, const Band& band, Stats& s) {
  if (claim.overlaps() == truth.overlaps) return;
  if (truth.how != Verdict::kLinearProgram) truth = JudgeExactly(p.obb, p.box);
  if (claim.overlaps() == truth.overlaps) return;  // a certificate and the LP cannot disagree; guard anyway
  ++s.family_disagreements[static_cast<int>(p.family)];
  const long double depth = std::fabs(truth.depth);
  if (claim.overlaps()) {
    ++s.false_overlaps;
    s.max_false_overlap_per_s = std::max(s.max_false_overlap_per_s, depth / SizeScale(p));
    s.max_false_overlap_per_m = std::max(s.max_false_overlap_per_m, depth / MagnitudeScale(p));
  } else {
    ++s.false_separations;
    s.max_false_separation_per_m = std::max(s.max_false_separation_per_m, depth / MagnitudeScale(p));
    if (p.family != PairFamily::kGeneric && p.gap == 0) ++s.touching_false_separations;
  }
  if (!band.Allows(claim.overlaps(), truth.depth, p)) ++s.outside_band;
}

void CountVerdict(const Truth& t, Stats& s) {
  s.lp += t.how == Verdict::kLinearProgram;
  s.axis_certificates += t.how == Verdict::kAxisCertificate;
  s.point_certificates += t.how == Verdict::kPointCertificate;
}

// Runs `count` pairs from `seed`; each pair is scored in double with
// `double_options` and, if `with_float`, in float with default options.
struct PropertyRun {
  Stats d, f;
};
PropertyRun RunPairs(std::uint64_t seed, std::uint64_t count, const SactOptions<double>& double_options,
                     bool with_float, const Band& double_band = kDoubleBand) {
  const int threads = std::max(1, omp_get_max_threads());
  std::vector<PropertyRun> per_thread(threads);
#pragma omp parallel for schedule(dynamic, 4096) num_threads(threads)
  for (std::uint64_t i = 0; i < count; ++i) {
    PropertyRun& run = per_thread[omp_get_thread_num()];
    const ObbAabbPair p = GeneratePair(seed, i);
    const SactResult claim = TestObbAabb(p.obb, p.box, double_options);
    Truth truth = Judge(p.obb, p.box, claim);
    CountVerdict(truth, run.d);
    ++run.d.pairs;
    ++run.d.family_pairs[static_cast<int>(p.family)];
    Score(p, claim, truth, double_band, run.d);
    if (!with_float) continue;
    const SactResult claim_f = TestObbAabb(p.obb.Cast<float>(), p.box.Cast<float>());
    CountVerdict(truth, run.f);
    ++run.f.pairs;
    ++run.f.family_pairs[static_cast<int>(p.family)];
    Score(p, claim_f, truth, kFloatBand, run.f);
  }
  PropertyRun total;
  for (const PropertyRun& r : per_thread) total.d.Merge(r.d), total.f.Merge(r.f);
  return total;
}

// One test for both precisions: the pairs' truths are shared, and ctest
// runs every test in its own process.
TEST(SactProperty, MillionPairsDoubleAndFloatStayInTheirBands) {
  const PropertyRun run = RunPairs(kSeed, kPairs, {}, true);
  const Stats& d = run.d;
  d.Print("double SACT, epsilon 1e-6");
  EXPECT_EQ(d.pairs, kPairs);
  EXPECT_EQ(d.outside_band, 0u);
  EXPECT_EQ(d.false_separations, 0u) << "with the epsilon, touching pairs must all come out as overlaps";
  // The test must have exercised contact: many LP verdicts, every family.
  EXPECT_GT(d.lp, kPairs / 20);
  for (int f = 0; f < kPairFamilyCount; ++f) EXPECT_GT(d.family_pairs[f], kPairs / 20) << f;
  EXPECT_GT(d.false_overlaps, 0u) << "the generator should reach into the epsilon band";

  const Stats& f = run.f;
  f.Print("float SACT, epsilon 1e-6, inputs rounded to float (same truths)");
  EXPECT_EQ(f.pairs, kPairs);
  EXPECT_EQ(f.outside_band, 0u);
}

TEST(SactPropertyArtifact, RowConventionBugFailsThePropertyTest) {
  // The artifact's SACT: rotation from axis columns, translation projected
  // on axis rows. It returned 317 wrong answers on 20,000 random pairs.
  SactOptions<double> artifact;
  artifact.convention = TranslationConvention::kArtifactRows;
  const PropertyRun wrong = RunPairs(kSeed + 1, 20'000, artifact, false);
  wrong.d.Print("artifact convention, 20,000 pairs");
  EXPECT_GT(wrong.d.outside_band, 20'000u / 100) << "the bug must show far outside any tolerance band";
  const PropertyRun right = RunPairs(kSeed + 1, 20'000, {}, false);
  EXPECT_EQ(right.d.outside_band, 0u);
}

TEST(SactPropertyEpsilon, WithoutEpsilonTouchingPairsCanComeOutSeparated) {
  // Why the epsilon: without it the OBB/AABB SACT is accurate to rounding
  // (R has no arithmetic in it), but rounding alone splits exactly touching
  // pairs both ways, so "touching counts as overlap" would not hold.
  SactOptions<double> no_epsilon;
  no_epsilon.parallel_epsilon = 0;
  const Band rounding_only{64, kDoubleUlp, 0};
  const PropertyRun run = RunPairs(kSeed + 2, kSmallRunPairs, no_epsilon, false, rounding_only);
  run.d.Print("double SACT, epsilon 0");
  EXPECT_EQ(run.d.outside_band, 0u) << "every error is a rounding-level one";
  EXPECT_GT(run.d.touching_false_separations, 0u);
  const PropertyRun with = RunPairs(kSeed + 2, kSmallRunPairs, {}, false);
  EXPECT_EQ(with.d.touching_false_separations, 0u);
}

TEST(SactPropertySpheres, SpherePretestsKeepTheAnswersInTheBand) {
  SactOptions<double> spheres;
  spheres.sphere_pretests = true;
  const PropertyRun run = RunPairs(kSeed + 3, kSmallRunPairs, spheres, false);
  run.d.Print("double SACT with sphere pre-tests");
  EXPECT_EQ(run.d.outside_band, 0u);
  EXPECT_EQ(run.d.false_separations, 0u);
}

}  // namespace
}  // namespace rc::test
