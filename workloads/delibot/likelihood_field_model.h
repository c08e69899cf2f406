#pragma once
// Likelihood-field model (Thrun et al. 6.4; AMCL's default): each beam's end
// point is scored by its distance to the nearest occupied cell, looked up in a
// precomputed distance field. No ray is cast, which is why it is much cheaper
// than the beam model (Beluga reports 20-30x). Max readings are skipped, as
// in AMCL. One distance-field fetch per beam counts as one node.
#include <memory>
#include <string>

#include "maps/distance_field.h"
#include "maps/occupancy_grid.h"
#include "workloads/delibot/beam_combination.h"
#include "workloads/delibot/sensor_model.h"

namespace rc {

struct LikelihoodFieldParams {
  double z_hit = 0.5;           // nav2 default
  double z_rand = 0.5;          // nav2 default
  double sigma_hit_m = 0.2;     // m, nav2 default
  double max_occ_dist_m = 2.0;  // m: distances are capped here (nav2 laser_likelihood_max_dist)
  double max_range_m = 10.0;    // m: readings at or beyond are skipped
  // false (AMCL's field): 0 everywhere inside occupied cells. true: an end
  // point inside a wall scores by its depth below the wall's face, as one in
  // front of it scores by its distance (a signed distance field). Signed
  // removes the unsigned field's forward bias on maps that match the world,
  // but loses on maps that draw open doors and glass as walls, so AMCL's
  // choice stays the default (docs/delibot.md, "Likelihood field, signed or
  // not"). See DistanceAt.
  bool signed_distance = false;
  // How an end point at or in an unknown cell scores. false (the default):
  // as a miss, at the distance cap, whatever is near. true ("edge"): the
  // edge of mapped free space is a surface, as the ray casters and
  // `rcbench simulate` treat it (they stop a ray at an unknown cell, as
  // AMCL's map_calc_range does): distances run to the nearest occupied or
  // unknown cell, and an end point inside unknown space scores by its depth
  // below the edge of free space. Where it matters, with numbers:
  // docs/real_logs_cautious_recipe.md ("unknown space as an edge").
  bool unknown_is_edge = false;
  BeamCombination combination = BeamCombination::kProduct;
  bool IsValid(std::string* error) const;
};

class LikelihoodFieldModel final : public SensorModel {
 public:
  LikelihoodFieldModel(const OccupancyGrid& grid, LikelihoodFieldParams params);
  std::string name() const override { return "likelihood"; }
  void LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan, const LaserGeometry& geometry,
                      const BeamSelection& beams, std::vector<double>& log_likelihoods,
                      SensorUpdateWork& work) override;
  // Always the product: the cube sum changes a weight by a factor of at
  // most about 6 per scan (30 beams), so resampling 500,000 particles by it
  // keeps an almost uniform sample and the dense first set is wasted.
  void SelectionLogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                               const LaserGeometry& geometry, const BeamSelection& beams,
                               std::vector<double>& log_likelihoods, SensorUpdateWork& work) override;
  // Branch and bound on the product: every beam's log density is at most
  // log(gauss_norm + floor), so a pose whose partial sum plus that bound
  // for its remaining beams falls below the keep-th best score found so far
  // cannot be among the best and is left unscored. Poses go in fixed
  // blocks, so the bound and the work are the same at any thread count;
  // the indices are those of a full scoring.
  std::vector<std::size_t> BestSelection(const std::vector<Pose2>& poses, const LaserScan& scan,
                                         const LaserGeometry& geometry, const BeamSelection& beams, std::size_t keep,
                                         SensorUpdateWork& work) override;
  // Distance (m) from a point to the face of the nearest occupied cell
  // (bilinear between cell centres, see the .cc); inside a wall, its depth
  // below the nearest free cell's face if signed_distance, else 0;
  // max_occ_dist_m outside the map, in unknown cells or beyond the cap.
  double DistanceAt(double x_m, double y_m) const;

 private:
  // Bilinear distance between the cell centres of `field` around (u, v)
  // (cell units, centres at integers), minus half a cell: 0 on the face of
  // a target cell; each sample capped so the far field sits at the cap.
  double FaceDistance(const DistanceField& field, double u, double v) const;
  // exp(-e^2 / 2) for the end point of a beam of range_m at angle_rad from
  // the sensor, e its distance in sigma_hit: the one computation Score and
  // BestSelection share, so both give the same totals bit for bit.
  double EndPointGauss(const Pose2& sensor, double range_m, double angle_rad) const;
  void Score(const std::vector<Pose2>& particles, const LaserScan& scan, const LaserGeometry& geometry,
             const BeamSelection& beams, BeamCombination combination, std::vector<double>& log_likelihoods,
             SensorUpdateWork& work) const;

  const OccupancyGrid* grid_;
  DistanceField field_;        // to the nearest occupied cell
  DistanceField depth_field_;  // to the nearest free cell (signed_distance only)
  LikelihoodFieldParams params_;
};

}  // namespace rc
