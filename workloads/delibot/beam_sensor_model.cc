#include "workloads/delibot/beam_sensor_model.h"

#include <cmath>

#include "robocore/ray_batch_recorded.h"

namespace rc {
namespace {
constexpr double kInvSqrt2Pi = 0.39894228040143267794;
}

bool BeamModelParams::IsValid(std::string* error) const {
  auto fail = [&](const char* what) {
    if (error) *error = what;
    return false;
  };
  if (!(z_hit >= 0 && z_short >= 0 && z_max >= 0 && z_rand >= 0)) return fail("mixture weights must be >= 0");
  if (!(z_rand > 0)) return fail("z_rand must be > 0 so that no beam has zero density");
  if (!(sigma_hit_m > 0)) return fail("sigma_hit must be > 0 m");
  if (!(lambda_short_per_m > 0)) return fail("lambda_short must be > 0 1/m");
  if (!(max_range_m > 0)) return fail("max_range must be > 0 m");
  return true;
}

double BeamLogDensity(const BeamModelParams& p, double z, double z_star) {
  double density = 0.0;
  if (z >= p.max_range_m) {
    density += p.z_max;
    // A max reading where the map also predicts nothing within range is the
    // hit case of an open view; the point mass above carries it.
    return std::log(density + 1e-300);
  }
  const double e = (z - z_star) / p.sigma_hit_m;
  density += p.z_hit * kInvSqrt2Pi / p.sigma_hit_m * std::exp(-0.5 * e * e);
  if (z < z_star) {
    const double normalizer = 1.0 - std::exp(-p.lambda_short_per_m * z_star);
    if (normalizer > 0.0)
      density += p.z_short * p.lambda_short_per_m * std::exp(-p.lambda_short_per_m * z) / normalizer;
  }
  density += p.z_rand / p.max_range_m;
  return std::log(density);
}

double BeamCubeProbability(const BeamModelParams& p, double z, double z_star) {
  const double range = z < p.max_range_m ? z : p.max_range_m;
  const double e = (range - z_star) / p.sigma_hit_m;
  double pz = p.z_hit * std::exp(-0.5 * e * e);
  if (range < z_star) pz += p.z_short * p.lambda_short_per_m * std::exp(-p.lambda_short_per_m * range);
  pz += range < p.max_range_m ? p.z_rand / p.max_range_m : p.z_max;
  return pz;
}

BeamSensorModel::BeamSensorModel(std::shared_ptr<const RayCastScene> scene, BeamModelParams params)
    : scene_(std::move(scene)), params_(params) {}

void BeamSensorModel::LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                                     const LaserGeometry& geometry, const BeamSelection& beams,
                                     std::vector<double>& log_likelihoods, SensorUpdateWork& work) {
  Score(particles, scan, geometry, beams, params_.combination, log_likelihoods, work);
}

void BeamSensorModel::SelectionLogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                                              const LaserGeometry& geometry, const BeamSelection& beams,
                                              std::vector<double>& log_likelihoods, SensorUpdateWork& work) {
  Score(particles, scan, geometry, beams, BeamCombination::kProduct, log_likelihoods, work);
}

void BeamSensorModel::Score(const std::vector<Pose2>& particles, const LaserScan& scan,
                            const LaserGeometry& geometry, const BeamSelection& beams,
                            BeamCombination combination, std::vector<double>& log_likelihoods,
                            SensorUpdateWork& work) {
  const int beams_per_particle = beams.Count(geometry.beam_count);
  const long n = static_cast<long>(particles.size());
  RayBatch& batch = work.batch;
  batch.max_range_m = params_.max_range_m;
  batch.queries.resize(static_cast<std::size_t>(n) * beams_per_particle);
  // Particle-major, beam-minor: the launch order of the CUDA kernels.
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const Pose2 sensor = SensorPose(particles[i], geometry);
    for (int k = 0; k < beams_per_particle; ++k) {
      RayQuery& q = batch.queries[static_cast<std::size_t>(i) * beams_per_particle + k];
      q.origin_x_m = sensor.x;
      q.origin_y_m = sensor.y;
      q.angle_rad = sensor.theta + geometry.BeamAngle(k * beams.beam_step);
    }
  }
  if (work.record_kernel) {
    RecordOptions record_options;
    record_options.sample = work.record_sample;
    CastRayBatchRecorded(*scene_, batch, work.hits, work.record, record_options);
  } else {
    CastRayBatch(*scene_, batch, work.hits);
  }
  log_likelihoods.resize(particles.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    ScanLikelihood scan_likelihood(combination);
    for (int k = 0; k < beams_per_particle; ++k) {
      const RayHit& hit = work.hits[static_cast<std::size_t>(i) * beams_per_particle + k];
      const double z = scan.ranges_m[static_cast<std::size_t>(k) * beams.beam_step];
      if (scan_likelihood.cube_sum())
        scan_likelihood.AddProbability(BeamCubeProbability(params_, z, hit.range_m));
      else
        scan_likelihood.AddLogDensity(BeamLogDensity(params_, z, hit.range_m));
    }
    log_likelihoods[i] = scan_likelihood.Log();
  }
  work.rays = batch.queries.size();
  work.beams_scored = beams_per_particle;
  work.nodes = TotalNodes(work.hits);
}

}  // namespace rc
