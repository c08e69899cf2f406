#pragma once
// Likelihood-field model (Thrun et al. 6.4; AMCL's default): each beam's end
// point is scored by its distance to the nearest occupied cell, looked up in a
// precomputed distance field. No ray is cast, which is why it is much cheaper
// than the beam model (Beluga reports 20-30x). Max readings are skipped, as
// in AMCL. One distance-field fetch per beam counts as one node.
#include <memory>

#include "maps/distance_field.h"
#include "maps/occupancy_grid.h"
#include "workloads/delibot/sensor_model.h"

namespace rc {

struct LikelihoodFieldParams {
  double z_hit = 0.5;             // nav2 default
  double z_rand = 0.5;            // nav2 default
  double sigma_hit_m = 0.2;       // m, nav2 default
  double max_occ_dist_m = 2.0;    // m: distances are capped here (nav2 laser_likelihood_max_dist)
  double max_range_m = 10.0;      // m: readings at or beyond are skipped
  bool IsValid(std::string* error) const;
};

class LikelihoodFieldModel final : public SensorModel {
 public:
  LikelihoodFieldModel(const OccupancyGrid& grid, LikelihoodFieldParams params);
  std::string name() const override { return "likelihood"; }
  void LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                      const LaserGeometry& geometry, const BeamSelection& beams,
                      std::vector<double>& log_likelihoods, SensorUpdateWork& work) override;
  // Distance (m) from a point to the face of the nearest occupied cell
  // (bilinear between cell centres, see the .cc); max_occ_dist_m
  // outside the map or beyond the cap.
  double DistanceAt(double x_m, double y_m) const;

 private:
  const OccupancyGrid* grid_;
  DistanceField field_;
  LikelihoodFieldParams params_;
};

}  // namespace rc
