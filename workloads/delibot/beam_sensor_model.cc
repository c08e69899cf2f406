#include "workloads/delibot/beam_sensor_model.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
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

BeamReadingDensity::BeamReadingDensity(const BeamModelParams& p, double z)
    : z_(z),
      max_reading_(z >= p.max_range_m),
      log_max_(std::log(p.z_max + 1e-300)),
      hit_scale_(p.z_hit * kInvSqrt2Pi / p.sigma_hit_m),
      sigma_hit_(p.sigma_hit_m),
      neg_lambda_(-p.lambda_short_per_m),
      short_numerator_(p.z_short * p.lambda_short_per_m * std::exp(-p.lambda_short_per_m * z)),
      rand_(p.z_rand / p.max_range_m) {}

double BeamReadingDensity::LogDensity(double z_star) const {
  // BeamLogDensity's steps; comments there.
  if (max_reading_) return log_max_;
  const double e = (z_ - z_star) / sigma_hit_;
  double density = hit_scale_ * std::exp(-0.5 * e * e);
  if (z_ < z_star) {
    const double normalizer = 1.0 - std::exp(neg_lambda_ * z_star);
    if (normalizer > 0.0) density += short_numerator_ / normalizer;
  }
  density += rand_;
  return std::log(density);
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

namespace {
// Rays per work unit of CastAndScore (whole particles, at least
// one). Units shrink as the update nears its end (a guided schedule): a
// unit takes 1/(2 x threads) of the particles left, within these bounds.
// Up to ~4096 rays (~300 microseconds) early on keeps the 32 lanes' fill
// and drain at a unit's ends near 0.5% of it and the unit's queries and
// hits (~130 KB) in the core's L2 between casting and scoring; down to
// ~512 rays at the end leaves one thread at most ~40 microseconds to finish
// alone while the other waits.
constexpr long kMaxRaysPerUnit = 4096;
constexpr long kMinRaysPerUnit = 512;
}  // namespace

void BeamSensorModel::FillQueries(const std::vector<Pose2>& particles, const LaserGeometry& geometry,
                                  const BeamSelection& beams, std::size_t begin, std::size_t end,
                                  RayQuery* queries) const {
  const auto per_particle = static_cast<std::size_t>(beams.Count(geometry.beam_count));
  for (std::size_t q = begin; q < end;) {
    const std::size_t i = q / per_particle;
    const Pose2 sensor = SensorPose(particles[i], geometry);
    for (const std::size_t stop = std::min(end, (i + 1) * per_particle); q < stop; ++q)
      *queries++ = BeamQuery(sensor, geometry, beams, static_cast<int>(q - i * per_particle));
  }
}

void BeamSensorModel::ScoreParticles(const LaserScan& scan, const BeamSelection& beams, BeamCombination combination,
                                     long begin, long end, const RayHit* hits,
                                     std::vector<double>& log_likelihoods) const {
  const int beams_per_particle = static_cast<int>(reading_densities_.size());
  for (long i = begin; i < end; ++i) {
    ScanLikelihood scan_likelihood(combination);
    const RayHit* particle_hits = hits + static_cast<std::size_t>(i - begin) * beams_per_particle;
    for (int k = 0; k < beams_per_particle; ++k) {
      if (scan_likelihood.cube_sum()) {
        const double z = scan.ranges_m[static_cast<std::size_t>(k) * beams.beam_step];
        scan_likelihood.AddProbability(BeamCubeProbability(params_, z, particle_hits[k].range_m));
      } else {
        scan_likelihood.AddLogDensity(reading_densities_[k].LogDensity(particle_hits[k].range_m));
      }
    }
    log_likelihoods[i] = scan_likelihood.Log();
  }
}

std::uint64_t BeamSensorModel::CastAndScore(const std::vector<Pose2>& particles, const LaserScan& scan,
                                            const LaserGeometry& geometry, const BeamSelection& beams,
                                            BeamCombination combination, long begin, long end,
                                            std::vector<double>& log_likelihoods) const {
  const int beams_per_particle = beams.Count(geometry.beam_count);
  const long per_particle = std::max(1, beams_per_particle);
  const long min_particles = std::max(1L, kMinRaysPerUnit / per_particle);
  const long max_particles = std::max(min_particles, kMaxRaysPerUnit / per_particle);
  std::atomic<long> next_particle{begin};
  std::uint64_t nodes = 0;  // an integer sum: the same at any thread count
#pragma omp parallel reduction(+ : nodes)
  {
    RayBatch unit;  // this thread's unit's queries, and their hits; reused unit after unit
    unit.max_range_m = params_.max_range_m;
    std::vector<RayHit> hits;
    const long threads = omp_get_num_threads();
    long first_particle = next_particle.load(std::memory_order_relaxed);
    while (first_particle < end) {
      const long size = std::clamp((end - first_particle) / (2 * threads), min_particles, max_particles);
      const long last_particle = std::min(end, first_particle + size);
      // Claim [first_particle, last_particle); on a race, first_particle is
      // reloaded and we retry.
      if (!next_particle.compare_exchange_weak(first_particle, last_particle, std::memory_order_relaxed)) continue;
      const std::size_t count = static_cast<std::size_t>(last_particle - first_particle) * beams_per_particle;
      unit.queries.resize(count);
      hits.resize(count);
      FillQueries(particles, geometry, beams, static_cast<std::size_t>(first_particle) * beams_per_particle,
                  static_cast<std::size_t>(last_particle) * beams_per_particle, unit.queries.data());
      CastRaySlice(*scene_, unit, 0, count, hits);
      ScoreParticles(scan, beams, combination, first_particle, last_particle, hits.data(), log_likelihoods);
      for (std::size_t i = 0; i < count; ++i) nodes += hits[i].nodes;
      first_particle = next_particle.load(std::memory_order_relaxed);
    }
  }
  return nodes;
}

void BeamSensorModel::Score(const std::vector<Pose2>& particles, const LaserScan& scan, const LaserGeometry& geometry,
                            const BeamSelection& beams, BeamCombination combination,
                            std::vector<double>& log_likelihoods, SensorUpdateWork& work) {
  const int beams_per_particle = beams.Count(geometry.beam_count);
  const long n = static_cast<long>(particles.size());
  reading_densities_.resize(static_cast<std::size_t>(beams_per_particle));
  for (int k = 0; k < beams_per_particle; ++k)
    reading_densities_[k] = BeamReadingDensity(params_, scan.ranges_m[static_cast<std::size_t>(k) * beams.beam_step]);
  // The hits of one launch at a time (work.hits), and never the whole
  // batch's queries: the first update of global localization casts tens of
  // millions of rays. A launch resizes them without clearing first: every
  // entry is overwritten, and zeroing them launch after launch showed in
  // profiles.
  log_likelihoods.resize(particles.size());
  const std::size_t rays = static_cast<std::size_t>(n) * beams_per_particle;
  work.rays = rays;
  work.beams_scored = beams_per_particle;
  if (!work.record_kernel) {
    work.hits.clear();
    work.nodes = CastAndScore(particles, scan, geometry, beams, combination, 0, n, log_likelihoods);
    return;
  }
  // Recorded: launch by launch, each filled, cast and scored before the
  // next, its queries filled segment by segment as the recorded kernel
  // casts them. Without price_launch, or within the limit, the batch is one
  // launch. Otherwise, launches of whole particles, each recorded and
  // handed on but the last, so that only one launch's record is alive at a
  // time; with estimate_launches, the full launches the launch sample
  // leaves out are cast and scored unit by unit without a record, as an
  // unrecorded update is (launch_sample.h).
  RecordOptions record_options = RecordOptionsFor(scene_->method(), work.record_choices);
  record_options.sample = work.record_sample;
  const std::size_t max_rays = std::max<std::size_t>(1, work.max_rays_per_launch);
  const auto beams_each = static_cast<std::size_t>(std::max(1, beams_per_particle));
  const bool split = work.price_launch && rays > max_rays;
  const std::size_t per_launch = split ? std::max<std::size_t>(1, max_rays / beams_each) * beams_each : rays;
  const std::size_t full_launches = split ? (rays - 1) / per_launch : 0;  // every launch but the last
  EstimatedLaunches estimated;
  std::uint64_t nodes = 0;
  // At least one launch, so that an empty batch leaves an empty record.
  for (std::size_t first = 0, index = 0; first < rays || index == 0; first += per_launch, ++index) {
    const std::size_t last = std::min(rays, first + per_launch);
    // The launch's particles; the last launch scores every particle left
    // (all of them when no beam is selected).
    const long begin = static_cast<long>(first / beams_each);
    const long end = last == rays ? n : static_cast<long>(last / beams_each);
    if (index < full_launches && work.estimate_launches && !work.launch_sample.Prices(index, full_launches)) {
      const std::uint64_t launch_nodes =
          CastAndScore(particles, scan, geometry, beams, combination, begin, end, log_likelihoods);
      nodes += launch_nodes;
      ++estimated.count;
      estimated.queries += last - first;
      estimated.nodes += launch_nodes;
      continue;
    }
    work.hits.resize(last - first);
    const QueryFiller fill = [&](std::size_t b, std::size_t e, RayQuery* out) {
      FillQueries(particles, geometry, beams, first + b, first + e, out);
    };
    CastRayBatchRecordedFilled(*scene_, last - first, params_.max_range_m, fill, work.hits, work.record,
                               record_options);
#pragma omp parallel for schedule(static) reduction(+ : nodes)
    for (long i = begin; i < end; ++i) {
      const RayHit* hits = work.hits.data() + static_cast<std::size_t>(i - begin) * beams_per_particle;
      ScoreParticles(scan, beams, combination, i, i + 1, hits, log_likelihoods);
      for (int k = 0; k < beams_per_particle; ++k) nodes += hits[k].nodes;
    }
    if (last < rays) {
      work.price_launch(work.record);
      ++estimated.like;
    }
  }
  if (estimated.count > 0) work.estimate_launches(estimated);
  work.nodes = nodes;
}

}  // namespace rc
