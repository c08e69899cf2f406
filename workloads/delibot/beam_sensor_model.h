#pragma once
// Beam range-finder model (Thrun et al., Probabilistic Robotics, 6.3): each
// beam's density is a mixture of a Gaussian around the ray-cast range (hit),
// an exponential for unexpected short readings (short), a point mass at the
// maximum range (max) and a uniform floor (rand). The beams combine as a
// product (log of each beam's mixture, summed) or by nav2 AMCL's cube sum.
#include <memory>

#include "robocore/ray_batch.h"
#include "workloads/delibot/beam_combination.h"
#include "workloads/delibot/sensor_model.h"

namespace rc {

struct BeamModelParams {
  // Mixture weights: nav2 AMCL's defaults (REFERENCE.md section 4).
  double z_hit = 0.5;
  double z_short = 0.05;
  double z_max = 0.05;
  double z_rand = 0.5;
  double sigma_hit_m = 0.2;         // m, nav2 default
  double lambda_short_per_m = 0.1;  // 1/m, nav2 default
  double max_range_m = 10.0;        // m: readings at or beyond are "max"
  BeamCombination combination = BeamCombination::kProduct;
  bool IsValid(std::string* error) const;
};

// Per-beam log density of measured range z given expected range z_star.
double BeamLogDensity(const BeamModelParams& p, double z, double z_star);
// nav2 AMCL's per-beam pz for its cube sum (beam_model.cpp): the hit term
// without the Gaussian's normalizer, the short term without its truncation
// normalizer, z_max for a reading at max range, else z_rand / max_range; a
// reading beyond max range counts as max range, as nav2 clamps it.
double BeamCubeProbability(const BeamModelParams& p, double z, double z_star);

// BeamLogDensity for one measured range z, with every term that depends on z
// alone (the max-reading case, the short term's numerator) computed once per
// scan and beam instead of once per particle. The same operations on the
// same values in the same order, so LogDensity(z_star) is bit-identical to
// BeamLogDensity(p, z, z_star) (tested).
class BeamReadingDensity {
 public:
  BeamReadingDensity() = default;
  BeamReadingDensity(const BeamModelParams& p, double z);
  double LogDensity(double z_star) const;

 private:
  double z_ = 0.0;
  bool max_reading_ = false;
  double log_max_ = 0.0;    // the whole answer for a max reading
  double hit_scale_ = 0.0;  // z_hit / (sqrt(2 pi) sigma_hit)
  double sigma_hit_ = 1.0;
  double neg_lambda_ = 0.0;       // -lambda_short (1/m)
  double short_numerator_ = 0.0;  // z_short * lambda_short * exp(-lambda_short z)
  double rand_ = 0.0;             // z_rand / max_range
};

class BeamSensorModel final : public SensorModel {
 public:
  BeamSensorModel(std::shared_ptr<const RayCastScene> scene, BeamModelParams params);
  std::string name() const override { return "beam"; }
  void LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan, const LaserGeometry& geometry,
                      const BeamSelection& beams, std::vector<double>& log_likelihoods,
                      SensorUpdateWork& work) override;
  // Always the product: the cube sum is too flat to pick a few thousand
  // particles out of a dense first set (see LikelihoodFieldModel).
  void SelectionLogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                               const LaserGeometry& geometry, const BeamSelection& beams,
                               std::vector<double>& log_likelihoods, SensorUpdateWork& work) override;
  const BeamModelParams& params() const { return params_; }

 private:
  void Score(const std::vector<Pose2>& particles, const LaserScan& scan, const LaserGeometry& geometry,
             const BeamSelection& beams, BeamCombination combination, std::vector<double>& log_likelihoods,
             SensorUpdateWork& work);
  // Queries [begin, end) of the particles' rays (particle-major,
  // beam-minor: query q is beam q % beams of particle q / beams), query
  // begin at queries[0]. A range may start or end inside a particle.
  void FillQueries(const std::vector<Pose2>& particles, const LaserGeometry& geometry, const BeamSelection& beams,
                   std::size_t begin, std::size_t end, RayQuery* queries) const;
  // Particles [begin, end), filled, cast (without a record) and scored in
  // units spread over the threads, each in its thread's own buffers (a
  // unit's queries and hits, still in the core's caches between the three;
  // nothing the size of the batch); returns their nodes.
  std::uint64_t CastAndScore(const std::vector<Pose2>& particles, const LaserScan& scan, const LaserGeometry& geometry,
                             const BeamSelection& beams, BeamCombination combination, long begin, long end,
                             std::vector<double>& log_likelihoods) const;
  // Particles [begin, end): their scan log-likelihoods from the cast hits,
  // particle begin's first at hits[0].
  void ScoreParticles(const LaserScan& scan, const BeamSelection& beams, BeamCombination combination, long begin,
                      long end, const RayHit* hits, std::vector<double>& log_likelihoods) const;

  std::shared_ptr<const RayCastScene> scene_;
  BeamModelParams params_;
  std::vector<BeamReadingDensity> reading_densities_;  // this scan's, one per selected beam
};

}  // namespace rc
