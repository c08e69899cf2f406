#include "workloads/delibot/likelihood_field_model.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>

namespace rc {
namespace {
constexpr double kInvSqrt2Pi = 0.39894228040143267794;
}

bool LikelihoodFieldParams::IsValid(std::string* error) const {
  auto fail = [&](const char* what) {
    if (error) *error = what;
    return false;
  };
  if (!(z_hit >= 0 && z_rand > 0)) return fail("z_hit must be >= 0 and z_rand > 0");
  if (!(sigma_hit_m > 0)) return fail("sigma_hit must be > 0 m");
  if (!(max_occ_dist_m > 0)) return fail("max_occ_dist must be > 0 m");
  if (!(max_range_m > 0)) return fail("max_range must be > 0 m");
  return true;
}

LikelihoodFieldModel::LikelihoodFieldModel(const OccupancyGrid& grid, LikelihoodFieldParams params)
    : grid_(&grid),
      field_(
          DistanceField::Build(grid, params.unknown_is_edge ? DistanceTarget::kBlocking : DistanceTarget::kOccupied)),
      params_(params) {
  if (params_.signed_distance || params_.unknown_is_edge)
    depth_field_ = DistanceField::Build(grid, DistanceTarget::kFree);
}

double LikelihoodFieldModel::FaceDistance(const DistanceField& field, double u, double v) const {
  const double r = grid_->resolution_m();
  const double fu = std::floor(u), fv = std::floor(v);
  const int i0 = static_cast<int>(fu), j0 = static_cast<int>(fv);
  const double tu = u - fu, tv = v - fv;
  // Capping each sample (the field is +inf on a map with no target cell)
  // half a cell above the cap keeps the far field at exactly the cap.
  const double sample_cap = params_.max_occ_dist_m + 0.5 * r;
  auto capped = [&](int i, int j) {
    i = std::clamp(i, 0, grid_->size_x() - 1);
    j = std::clamp(j, 0, grid_->size_y() - 1);
    return std::min<double>(field.At(i, j), sample_cap);
  };
  const double d = (1 - tu) * ((1 - tv) * capped(i0, j0) + tv * capped(i0, j0 + 1)) +
                   tu * ((1 - tv) * capped(i0 + 1, j0) + tv * capped(i0 + 1, j0 + 1));
  return std::clamp(d - 0.5 * r, 0.0, params_.max_occ_dist_m);
}

double LikelihoodFieldModel::DistanceAt(double x_m, double y_m) const {
  // The field holds centre-to-centre distances at cell centres ((i + 0.5) r).
  // A beam that ends exactly on a wall face lies half a cell from the centre
  // of the wall cell, so a nearest-cell lookup scores it as r (if the end
  // point falls in the free cell) or 0 (in the wall cell): the best-scoring
  // pose puts end points inside the walls, half a cell too far (AMCL has this
  // bias). Interpolating bilinearly between the four surrounding centres and
  // subtracting half a cell gives the distance to the wall's face instead:
  // 0 on the face, growing one-for-one away from it.
  const double r = grid_->resolution_m();
  if (!(x_m >= 0 && y_m >= 0 && x_m < grid_->extent_x_m() && y_m < grid_->extent_y_m())) return params_.max_occ_dist_m;
  // An end point in an unknown cell is as far from evidence as one off the
  // map (AMCL scores those at the cap). The field measures distance to
  // occupied cells only, so without this an end point in the unmapped space
  // behind a wall scores as if it hit the wall: in Wean Hall a particle in a
  // doorway pocket, 2.6 m beside the robot's corridor, then explains the
  // scan better than the true pose. With unknown_is_edge the unknown cells
  // are surfaces instead, and an end point inside unknown space scores by
  // its depth below the edge of free space: deep in the space behind a
  // metre-thick wall it is still a miss.
  const double u = x_m / r - 0.5, v = y_m / r - 0.5;
  if (grid_->At(static_cast<int>(x_m / r), static_cast<int>(y_m / r)) == CellState::kUnknown)
    return params_.unknown_is_edge ? FaceDistance(depth_field_, u, v) : params_.max_occ_dist_m;
  const double outside = FaceDistance(field_, u, v);
  // Unsigned (AMCL), the distance is 0 throughout a wall, so an end point
  // that goes through a wall's face costs nothing while one short of it
  // costs: with range noise and a laser that looks forward, the
  // best-scoring pose sits forward of the truth (6.6 cm on the simulated
  // office trace at sigma_hit 0.05 m, 10 cm at 0.2 m, with our field and
  // with MRPT's, against 1 cm for the beam model). Scoring the depth below
  // the face too makes the score symmetric about the face.
  if (!params_.signed_distance || outside > 0) return outside;
  return FaceDistance(depth_field_, u, v);
}

double LikelihoodFieldModel::EndPointGauss(const Pose2& sensor, double range_m, double angle_rad) const {
  const double d = DistanceAt(sensor.x + range_m * std::cos(angle_rad), sensor.y + range_m * std::sin(angle_rad));
  const double e = d / params_.sigma_hit_m;
  return std::exp(-0.5 * e * e);
}

void LikelihoodFieldModel::LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                                          const LaserGeometry& geometry, const BeamSelection& beams,
                                          std::vector<double>& log_likelihoods, SensorUpdateWork& work) {
  Score(particles, scan, geometry, beams, params_.combination, log_likelihoods, work);
}

void LikelihoodFieldModel::SelectionLogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                                                   const LaserGeometry& geometry, const BeamSelection& beams,
                                                   std::vector<double>& log_likelihoods, SensorUpdateWork& work) {
  Score(particles, scan, geometry, beams, BeamCombination::kProduct, log_likelihoods, work);
}

void LikelihoodFieldModel::Score(const std::vector<Pose2>& particles, const LaserScan& scan,
                                 const LaserGeometry& geometry, const BeamSelection& beams, BeamCombination combination,
                                 std::vector<double>& log_likelihoods, SensorUpdateWork& work) const {
  const int beams_per_particle = beams.Count(geometry.beam_count);
  const long n = static_cast<long>(particles.size());
  log_likelihoods.resize(particles.size());
  const double gauss_norm = params_.z_hit * kInvSqrt2Pi / params_.sigma_hit_m;
  const double floor_density = params_.z_rand / params_.max_range_m;
  long used_beams = 0;
  for (int k = 0; k < beams_per_particle; ++k)
    used_beams += scan.ranges_m[static_cast<std::size_t>(k) * beams.beam_step] < params_.max_range_m;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const Pose2 sensor = SensorPose(particles[i], geometry);
    ScanLikelihood scan_likelihood(combination);
    for (int k = 0; k < beams_per_particle; ++k) {
      const double z = scan.ranges_m[static_cast<std::size_t>(k) * beams.beam_step];
      if (z >= params_.max_range_m) continue;
      const double gauss = EndPointGauss(sensor, z, sensor.theta + geometry.BeamAngle(k * beams.beam_step));
      if (scan_likelihood.cube_sum())
        scan_likelihood.AddProbability(params_.z_hit * gauss + floor_density);
      else
        scan_likelihood.AddLogDensity(std::log(gauss_norm * gauss + floor_density));
    }
    log_likelihoods[i] = scan_likelihood.Log();
  }
  work.hits.clear();
  work.rays = static_cast<std::uint64_t>(used_beams) * particles.size();
  work.nodes = work.rays;
  work.beams_scored = static_cast<int>(used_beams);
}

std::vector<std::size_t> LikelihoodFieldModel::BestSelection(const std::vector<Pose2>& poses, const LaserScan& scan,
                                                             const LaserGeometry& geometry, const BeamSelection& beams,
                                                             std::size_t keep, SensorUpdateWork& work) {
  // Poses per block: the bound is raised between blocks. Any size gives the
  // same indices; this one amortises the bound's update.
  constexpr std::size_t kBlock = 65536;
  const int beams_per_particle = beams.Count(geometry.beam_count);
  std::vector<double> ranges;  // the used beams' ranges, in Score's order
  std::vector<int> used;
  for (int k = 0; k < beams_per_particle; ++k) {
    const double z = scan.ranges_m[static_cast<std::size_t>(k) * beams.beam_step];
    if (z >= params_.max_range_m) continue;
    used.push_back(k);
    ranges.push_back(z);
  }
  const int m = static_cast<int>(used.size());
  // Computed as Score computes the product, so a scored pose's total is
  // bit for bit the one SelectionLogLikelihoods gives.
  const double gauss_norm = params_.z_hit * kInvSqrt2Pi / params_.sigma_hit_m;
  const double floor_density = params_.z_rand / params_.max_range_m;
  const double beam_max = std::log(gauss_norm + floor_density);  // gauss <= 1
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> scores(poses.size(), -inf);
  std::vector<double> best;  // the keep best scores so far
  double bound = -inf;       // the keep-th best so far: the final one is at least this
  std::uint64_t queries = 0;
  for (std::size_t begin = 0; begin < poses.size(); begin += kBlock) {
    const long first = static_cast<long>(begin), last = static_cast<long>(std::min(poses.size(), begin + kBlock));
    long block_queries = 0;
#pragma omp parallel for schedule(static) reduction(+ : block_queries)
    for (long i = first; i < last; ++i) {
      const Pose2 sensor = SensorPose(poses[i], geometry);
      double sum = 0.0;
      int b = 0;
      for (; b < m; ++b) {
        // The rounding slack keeps the bound above every sum the remaining
        // beams can reach in floating point.
        const double reachable = sum + (m - b) * beam_max;
        if (reachable + 1e-9 * (1.0 + std::abs(sum) + (m - b) * std::abs(beam_max)) < bound) break;
        const double gauss =
            EndPointGauss(sensor, ranges[static_cast<std::size_t>(b)],
                          sensor.theta + geometry.BeamAngle(used[static_cast<std::size_t>(b)] * beams.beam_step));
        sum += std::log(gauss_norm * gauss + floor_density);
      }
      block_queries += b;
      if (b == m) scores[static_cast<std::size_t>(i)] = sum;
    }
    queries += static_cast<std::uint64_t>(block_queries);
    if (keep == 0) continue;
    for (long i = first; i < last; ++i)
      if (scores[static_cast<std::size_t>(i)] > -inf) best.push_back(scores[static_cast<std::size_t>(i)]);
    if (best.size() >= keep) {
      std::nth_element(best.begin(), best.begin() + static_cast<std::ptrdiff_t>(keep - 1), best.end(),
                       std::greater<double>());
      best.resize(keep);
      bound = best.back();
    }
  }
  work.hits.clear();
  work.rays = queries;
  work.nodes = queries;
  work.beams_scored = m;
  return BestIndices(scores, keep);
}

}  // namespace rc
