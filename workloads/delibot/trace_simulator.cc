#include "workloads/delibot/trace_simulator.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <stdexcept>
#include <utility>

#include "common/pose_algebra.h"
#include "common/random_stream.h"
#include "robocore/ray_cast.h"
#include "workloads/delibot/sensor_model.h"

namespace rc {
namespace {

// The stream index of RandomStream(seed, kSimulation, step, index) names
// the noise source in its high 32 bits and the member (beam, person) in the
// low 32 bits. Source 0 with step = waypoint number is the route's waypoint
// sequence (DrawRouteWaypoint).
enum class NoiseSource : std::uint64_t {
  kBeam = 1,        // step = record, member = beam
  kOdometry = 2,    // step = record
  kPersonGoal = 3,  // step = goal number, member = person
  kKidnap = 4,      // step = record
};

RandomStream SimulationStream(std::uint64_t seed, std::uint64_t step, NoiseSource source, std::uint64_t member) {
  return RandomStream(seed, StreamPurpose::kSimulation, step, (static_cast<std::uint64_t>(source) << 32) | member);
}

// A kidnap should be unmistakable: the new pose is at least this far (m)
// from the old one when the reachable space allows it.
constexpr double kMinKidnapJumpM = 1.0;
constexpr int kKidnapDraws = 64;
// Goals that coincide with the current position are skipped; this many in a
// row means the reachable space is degenerate (a bug upstream).
constexpr int kMaxSkippedGoals = 10000;

// Drives a disc along collision-free legs to a sequence of goals: turn in
// place towards the next vertex, then drive straight to it. Time is consumed
// exactly, across as many vertices and legs as fit in one step.
class RouteFollower {
 public:
  // Goal 0 is the start position; an empty optional ends the route.
  using GoalSource = std::function<std::optional<RoutePoint>(std::uint64_t goal_number)>;

  RouteFollower(const ReachableFreeSpace& space, GoalSource goals, double speed_mps, double turn_rate_radps)
      : space_(&space), goals_(std::move(goals)), speed_mps_(speed_mps), turn_rate_radps_(turn_rate_radps) {
    const std::optional<RoutePoint> start = goals_(0);
    if (!start) throw std::logic_error("route follower without a start goal");
    position_ = *start;
    next_goal_ = 1;
    StartNextLeg();
    // Face the first segment so that the trace does not open with a turn.
    if (!leg_.empty()) heading_ = std::atan2(leg_.front().y_m - position_.y_m, leg_.front().x_m - position_.x_m);
  }

  Pose2 pose() const { return {position_.x_m, position_.y_m, heading_}; }
  bool finished() const { return finished_; }

  void Advance(double dt_s) {
    double remaining_s = dt_s;
    while (remaining_s > 0.0 && !finished_) {
      const RoutePoint target = leg_.front();
      const double dx = target.x_m - position_.x_m, dy = target.y_m - position_.y_m;
      const double distance_m = std::hypot(dx, dy);
      if (distance_m > 0.0) {
        const double desired = std::atan2(dy, dx);
        const double turn = WrapAngle(desired - heading_);
        const double turn_s = std::abs(turn) / turn_rate_radps_;  // 0 for an infinite rate
        if (turn_s > remaining_s) {
          heading_ = WrapAngle(heading_ + std::copysign(turn_rate_radps_ * remaining_s, turn));
          return;
        }
        heading_ = desired;
        remaining_s -= turn_s;
        const double drive_s = distance_m / speed_mps_;
        if (drive_s > remaining_s) {
          const double step_m = speed_mps_ * remaining_s;
          position_.x_m += dx / distance_m * step_m;
          position_.y_m += dy / distance_m * step_m;
          return;
        }
        remaining_s -= drive_s;
      }
      position_ = target;  // exactly, so legs join at their vertices
      leg_.pop_front();
      if (leg_.empty()) StartNextLeg();
    }
  }

  // Moves the robot without driving; it then heads for its current goal
  // from the new pose.
  void Teleport(const Pose2& pose) {
    position_ = {pose.x, pose.y};
    heading_ = WrapAngle(pose.theta);
    leg_.clear();
    if (finished_) return;
    const std::vector<RoutePoint> path = space_->PlanPath(position_, goal_);
    leg_.assign(path.begin() + 1, path.end());
    if (leg_.empty()) StartNextLeg();
  }

 private:
  void StartNextLeg() {
    for (int skipped = 0; skipped < kMaxSkippedGoals; ++skipped) {
      const std::optional<RoutePoint> goal = goals_(next_goal_++);
      if (!goal) {
        finished_ = true;
        return;
      }
      if (goal->x_m == position_.x_m && goal->y_m == position_.y_m) continue;
      goal_ = *goal;
      const std::vector<RoutePoint> path = space_->PlanPath(position_, goal_);
      leg_.assign(path.begin() + 1, path.end());
      return;
    }
    throw std::logic_error("every goal coincides with the current position");
  }

  const ReachableFreeSpace* space_;
  GoalSource goals_;
  double speed_mps_;
  double turn_rate_radps_;
  RoutePoint position_;
  double heading_ = 0.0;
  RoutePoint goal_;
  std::deque<RoutePoint> leg_;  // remaining vertices of the current leg
  std::uint64_t next_goal_ = 0;
  bool finished_ = false;
};

// Distance along the ray to a disc, or +inf if the ray misses it or starts
// inside it (a person standing on the laser is not seen; see the header).
double RayDiscDistance(double ox, double oy, double dx, double dy, const Pose2& centre, double radius_m) {
  const double fx = ox - centre.x, fy = oy - centre.y;
  const double c = fx * fx + fy * fy - radius_m * radius_m;
  if (c <= 0.0) return std::numeric_limits<double>::infinity();
  const double b = fx * dx + fy * dy;
  const double discriminant = b * b - c;
  if (discriminant < 0.0 || b >= 0.0) return std::numeric_limits<double>::infinity();
  return -b - std::sqrt(discriminant);
}

// Applies the beam noise model to the true range. Four values are drawn for
// every beam whatever the options, so turning one source on or off does not
// change the draws of the others.
float NoisyRange(float true_range_m, const SimulationOptions& options, RandomStream& stream) {
  const double max_range_m = options.geometry.max_range_m;
  const double dropout_draw = stream.Uniform();
  const double short_draw = stream.Uniform();
  const double short_fraction = stream.Uniform();
  const double gaussian = stream.Gaussian();
  if (dropout_draw < options.max_range_dropout_probability) return static_cast<float>(max_range_m);
  double reading = true_range_m;
  if (short_draw < options.short_reading_probability) {
    reading = short_fraction * true_range_m;
  } else if (reading < max_range_m) {  // a no-return stays one
    reading += options.range_sigma_m * gaussian;
  }
  return static_cast<float>(std::clamp(reading, 0.0, max_range_m));
}

// The odometry's view of a true increment (robot frame of the previous
// record): translation scaled by (1 + bias + noise), rotation by
// (1 + noise), and a heading drift proportional to the distance driven.
Pose2 OdometryIncrement(const Pose2& true_increment, const SimulationOptions& options, RandomStream& stream) {
  const double translation_noise = stream.Gaussian();
  const double rotation_noise = stream.Gaussian();
  const double distance_m = std::hypot(true_increment.x, true_increment.y);
  const double scale = 1.0 + options.odometry_translation_bias + options.odometry_translation_sigma * translation_noise;
  return {true_increment.x * scale, true_increment.y * scale,
          true_increment.theta * (1.0 + options.odometry_rotation_sigma * rotation_noise) +
              options.odometry_heading_drift_rad_per_m * distance_m};
}

Pose2 KidnapPose(const ReachableFreeSpace& space, const Pose2& from, std::uint64_t seed, int record) {
  RandomStream stream = SimulationStream(seed, static_cast<std::uint64_t>(record), NoiseSource::kKidnap, 0);
  RoutePoint best{};
  double best_jump_m = -1.0;
  for (int draw = 0; draw < kKidnapDraws && best_jump_m < kMinKidnapJumpM; ++draw) {
    const RoutePoint p = space.DrawPoint(stream);
    const double jump_m = std::hypot(p.x_m - from.x, p.y_m - from.y);
    if (jump_m > best_jump_m) {
      best = p;
      best_jump_m = jump_m;
    }
  }
  return {best.x_m, best.y_m, WrapAngle(stream.Uniform(-kPi, kPi))};
}

}  // namespace

void SimulationOptions::DisableNoise() {
  range_sigma_m = 0.0;
  short_reading_probability = 0.0;
  max_range_dropout_probability = 0.0;
  people_count = 0;
  odometry_translation_sigma = 0.0;
  odometry_rotation_sigma = 0.0;
  odometry_translation_bias = 0.0;
  odometry_heading_drift_rad_per_m = 0.0;
}

bool SimulationOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error != nullptr) *error = message;
    return false;
  };
  auto in = [](double v, double lo, double hi) { return v >= lo && v <= hi; };  // false for NaN
  if (geometry.beam_count < 1 || geometry.beam_count > 100000) return fail("geometry.beam_count must be in [1, 10^5]");
  if (!(geometry.max_range_m > 0.0) || !std::isfinite(geometry.max_range_m))
    return fail("geometry.max_range_m must be a positive number of metres");
  if (!in(geometry.offset_forward_m, 0.0, 10.0)) return fail("geometry.offset_forward_m must be in [0, 10] m");
  if (!std::isfinite(geometry.angle_min_rad) || !std::isfinite(geometry.angle_increment_rad))
    return fail("geometry angles must be finite");
  if (!(robot_radius_m > 0.0 && robot_radius_m <= 10.0)) return fail("robot_radius_m must be in (0, 10] m");
  if (waypoint_count < 2 || waypoint_count > 1000000) return fail("waypoint_count must be in [2, 10^6]");
  if (!(speed_mps > 0.0 && speed_mps <= 10.0)) return fail("speed_mps must be in (0, 10] m/s");
  if (!(turn_rate_radps > 0.0 && turn_rate_radps <= 20.0)) return fail("turn_rate_radps must be in (0, 20] rad/s");
  if (!(laser_rate_hz > 0.0 && laser_rate_hz <= 1000.0)) return fail("laser_rate_hz must be in (0, 1000] Hz");
  if (record_count < 1 || record_count > 10000000) return fail("record_count must be in [1, 10^7]");
  if (!in(range_sigma_m, 0.0, 10.0)) return fail("range_sigma_m must be in [0, 10] m");
  if (!in(short_reading_probability, 0.0, 1.0)) return fail("short_reading_probability must be in [0, 1]");
  if (!in(max_range_dropout_probability, 0.0, 1.0)) return fail("max_range_dropout_probability must be in [0, 1]");
  if (people_count < 0 || people_count > 1000) return fail("people_count must be in [0, 1000]");
  if (!(people_radius_m > 0.0 && people_radius_m <= 2.0)) return fail("people_radius_m must be in (0, 2] m");
  if (!(people_speed_mps > 0.0 && people_speed_mps <= 10.0)) return fail("people_speed_mps must be in (0, 10] m/s");
  if (!in(odometry_translation_sigma, 0.0, 1.0)) return fail("odometry_translation_sigma must be in [0, 1]");
  if (!in(odometry_rotation_sigma, 0.0, 1.0)) return fail("odometry_rotation_sigma must be in [0, 1]");
  if (!in(odometry_translation_bias, -0.5, 0.5)) return fail("odometry_translation_bias must be in [-0.5, 0.5]");
  if (!in(odometry_heading_drift_rad_per_m, -1.0, 1.0))
    return fail("odometry_heading_drift_rad_per_m must be in [-1, 1] rad/m");
  if (odometry_start &&
      (!std::isfinite(odometry_start->x) || !std::isfinite(odometry_start->y) || !std::isfinite(odometry_start->theta)))
    return fail("odometry_start must be finite");
  if (kidnap_record != -1 && (kidnap_record < 1 || kidnap_record >= record_count))
    return fail("kidnap_record must be -1 (off) or in [1, record_count)");
  return true;
}

SimulatedTrace SimulateTrace(const OccupancyGrid& grid, const SimulationOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("simulation options: " + error);
  const LaserGeometry& geometry = options.geometry;

  SimulatedTrace result;
  result.planning_radius_m = std::max(options.robot_radius_m, geometry.offset_forward_m + kLaserWallClearanceM);
  const ReachableFreeSpace space(grid, result.planning_radius_m);
  result.route = PlanFreeSpaceRoute(space, options.waypoint_count, options.seed);

  // The robot visits the route's waypoints, then (unless told to stop)
  // continues the same seeded waypoint sequence.
  const std::vector<RoutePoint>& waypoints = result.route.waypoints;
  RouteFollower robot(
      space,
      [&](std::uint64_t goal) -> std::optional<RoutePoint> {
        if (goal < waypoints.size()) return waypoints[goal];
        if (options.stop_at_route_end) return std::nullopt;
        return DrawRouteWaypoint(space, options.seed,
                                 static_cast<std::uint64_t>(options.waypoint_count) + (goal - waypoints.size()));
      },
      options.speed_mps, options.turn_rate_radps);
  std::vector<RouteFollower> people;
  for (int p = 0; p < options.people_count; ++p) {
    const std::uint64_t seed = options.seed, member = static_cast<std::uint64_t>(p);
    // People walk forever and turn on the spot without delay.
    people.emplace_back(
        space,
        [&space, seed, member](std::uint64_t goal) -> std::optional<RoutePoint> {
          RandomStream stream = SimulationStream(seed, goal, NoiseSource::kPersonGoal, member);
          return space.DrawCellCentre(stream);
        },
        options.people_speed_mps, std::numeric_limits<double>::infinity());
  }

  result.trace.source_path = "simulated";
  result.trace.format = "cmu";
  result.trace.geometry = geometry;
  const double dt_s = 1.0 / options.laser_rate_hz;
  Pose2 truth = robot.pose();
  Pose2 odometry = options.odometry_start ? *options.odometry_start : Compose(kDefaultOdometryFrame, truth);
  for (int record = 0; record < options.record_count; ++record) {
    const auto step = static_cast<std::uint64_t>(record);
    if (record > 0) {
      robot.Advance(dt_s);
      for (RouteFollower& person : people) person.Advance(dt_s);
      const Pose2 driven = robot.pose();
      RandomStream odometry_stream = SimulationStream(options.seed, step, NoiseSource::kOdometry, 0);
      odometry = Compose(odometry, OdometryIncrement(Between(truth, driven), options, odometry_stream));
      truth = driven;
      if (record == options.kidnap_record) {
        // After driving, so the odometry reports the motion but not the jump.
        truth = KidnapPose(space, truth, options.seed, record);
        robot.Teleport(truth);
        result.kidnap_record = record;
      }
    }

    LaserScan scan;
    scan.time_s = record / options.laser_rate_hz;
    scan.odometry = odometry;
    scan.ranges_m.resize(static_cast<std::size_t>(geometry.beam_count));
    const Pose2 sensor = SensorPose(truth, geometry);
    NoFetchVisitor no_fetch;
    for (int beam = 0; beam < geometry.beam_count; ++beam) {
      const double angle = sensor.theta + geometry.BeamAngle(beam);
      float range_m = CastDda(grid, sensor.x, sensor.y, angle, geometry.max_range_m, no_fetch).range_m;
      const double dx = std::cos(angle), dy = std::sin(angle);
      for (const RouteFollower& person : people) {
        const double d = RayDiscDistance(sensor.x, sensor.y, dx, dy, person.pose(), options.people_radius_m);
        if (d < range_m) range_m = static_cast<float>(d);
      }
      RandomStream beam_stream =
          SimulationStream(options.seed, step, NoiseSource::kBeam, static_cast<std::uint64_t>(beam));
      scan.ranges_m[static_cast<std::size_t>(beam)] = NoisyRange(range_m, options, beam_stream);
    }
    result.trace.scans.push_back(std::move(scan));
    result.ground_truth.push_back({result.trace.scans.back().time_s, truth, 0});
    if (options.stop_at_route_end && robot.finished()) break;
  }
  return result;
}

}  // namespace rc
