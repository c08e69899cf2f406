#pragma once
// The sensor-model interface of the particle filter (Beluga's split: motion
// model, sensor model and resampling policy are independent components).
// A sensor model turns one scan into a log-likelihood per particle. It never
// multiplies raw beam probabilities: per-beam densities are summed as logs.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/angles.h"
#include "robocore/kernel_record.h"
#include "robocore/launch_sample.h"
#include "robocore/ray_batch.h"
#include "robocore/ray_batch_recorded.h"
#include "traces/sensor_trace.h"
#include "workloads/delibot/best_indices.h"

namespace rc {

// The beams a filter update uses: every beam_step-th beam of the scan,
// starting at beam 0.
struct BeamSelection {
  int beam_step = 1;
  int Count(int beam_count) const { return (beam_count + beam_step - 1) / beam_step; }
};

// Rays per recorded kernel launch, at most (a rule that acts as a cost
// parameter: a batch above it is priced as that many launches, each with
// its own launch overhead and tail). Unit: rays; range: >= 1. Source:
// assumption, that a GPU implementation bounds one launch's device buffers
// (queries, hits: 32 bytes a ray) to tens of MB. DeliBot's working sets
// (2000 particles x 30 to 180 beams) stay far below it; a map-sized first
// set scored by the beam model (850,000 particles x 30 beams) is split,
// which keeps pricing's memory bounded (docs/pricing.md).
inline constexpr std::size_t kMaxRaysPerLaunch = std::size_t{1} << 20;

// What one update asked of the kernels, for timelines and backends.
struct SensorUpdateWork {
  std::uint64_t rays = 0;   // queries issued (rays, or endpoint lookups)
  std::uint64_t nodes = 0;  // nodes (cells or distance samples) fetched
  int beams_scored = 0;     // beams that entered each particle's likelihood
  // The hits of the last update's last recorded launch (the whole update
  // when it is one launch); empty after an unrecorded update and for models
  // without rays. An update never holds more than one launch's hits, nor
  // all of a launch's queries at once.
  std::vector<RayHit> hits;
  // When record_kernel is set, ray-casting models also fill `record` with
  // every query's node fetches (run once), for the backends to price.
  bool record_kernel = false;
  AddressSample record_sample;      // whose addresses the record keeps
  RayKernelChoices record_choices;  // the device's cell size and march program (a preset's "kernel")
  KernelRecord record;
  // With price_launch set, a recorded batch of more than max_rays_per_launch
  // rays runs as several launches of whole particles, at most that many rays
  // each (one particle's beams if they alone exceed it): each but the last is
  // handed to price_launch as soon as it is recorded (and its record reused),
  // the last stays in `record`. Unset: one launch, whatever its size.
  std::function<void(const KernelRecord&)> price_launch;
  std::size_t max_rays_per_launch = kMaxRaysPerLaunch;
  // With estimate_launches also set, only the full launches launch_sample
  // prices are recorded and handed to price_launch; the others are cast
  // without a record and, after the batch's last full launch, handed to
  // estimate_launches (robocore/launch_sample.h).
  LaunchSample launch_sample;
  std::function<void(const EstimatedLaunches&)> estimate_launches;
};

class SensorModel {
 public:
  virtual ~SensorModel() = default;
  virtual std::string name() const = 0;
  // Writes one log-likelihood per particle into log_likelihoods.
  virtual void LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan, const LaserGeometry& geometry,
                              const BeamSelection& beams, std::vector<double>& log_likelihoods,
                              SensorUpdateWork& work) = 0;
  // The same, for the update that cuts a dense initial set
  // (--initial-particles) down to the working set: it must pick a few
  // thousand particles out of hundreds of thousands, so a model whose scan
  // likelihood is deliberately flat scores this update its sharp way.
  virtual void SelectionLogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                                       const LaserGeometry& geometry, const BeamSelection& beams,
                                       std::vector<double>& log_likelihoods, SensorUpdateWork& work) {
    LogLikelihoods(particles, scan, geometry, beams, log_likelihoods, work);
  }
  // Indices of the `keep` poses with the highest SelectionLogLikelihoods,
  // best first, ties to the lower index (BestIndices): exactly those of a
  // full scoring, though a model may leave unscored the poses a bound
  // proves cannot be among them. work.rays counts the queries made.
  virtual std::vector<std::size_t> BestSelection(const std::vector<Pose2>& poses, const LaserScan& scan,
                                                 const LaserGeometry& geometry, const BeamSelection& beams,
                                                 std::size_t keep, SensorUpdateWork& work) {
    std::vector<double> scores;
    SelectionLogLikelihoods(poses, scan, geometry, beams, scores, work);
    return BestIndices(scores, keep);
  }
  // A model with a global-localization stage and a tracking stage
  // (staged_sensor_model.h) switches when the localizer calls BeginTracking,
  // once one hypothesis is left. A one-stage model ignores the call.
  virtual bool HasTrackingStage() const { return false; }
  // The model that compares places far apart, as global localization does
  // (a staged model's global stage): what a claim audit scores with
  // (claim_audit.h).
  virtual SensorModel& PlaceModel() { return *this; }
  virtual bool Tracking() const { return false; }
  virtual void BeginTracking() {}
};

// Sensor origin (m) and beam angle (rad) in the map frame for a robot pose.
inline Pose2 SensorPose(const Pose2& robot, const LaserGeometry& geometry) {
  return {robot.x + geometry.offset_forward_m * std::cos(robot.theta),
          robot.y + geometry.offset_forward_m * std::sin(robot.theta), robot.theta};
}

// The ray of selected beam k (0-based among the selected) from a sensor at
// `sensor` (SensorPose): a scan's queries, beam-minor.
inline RayQuery BeamQuery(const Pose2& sensor, const LaserGeometry& geometry, const BeamSelection& beams, int k) {
  return {sensor.x, sensor.y, sensor.theta + geometry.BeamAngle(k * beams.beam_step)};
}

}  // namespace rc
