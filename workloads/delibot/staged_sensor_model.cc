#include "workloads/delibot/staged_sensor_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rc {
namespace {

// log sum_i exp(v_i), -inf for no finite term.
double LogSumExp(const std::vector<double>& v) {
  double most = -std::numeric_limits<double>::infinity();
  for (double x : v) most = std::max(most, x);
  if (!std::isfinite(most)) return most;
  double sum = 0.0;
  for (double x : v) sum += std::exp(x - most);
  return most + std::log(sum);
}

// In place: global[i] = log((exp(global[i] - G) + exp(tracking[i] - T)) / 2)
// with G, T each model's log normalizer; a model whose scores are all -inf
// leaves the other's posterior alone.
void MixPosteriors(std::vector<double>& global, const std::vector<double>& tracking) {
  const double g = LogSumExp(global), t = LogSumExp(tracking);
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < global.size(); ++i) {
    const double x = std::isfinite(g) ? global[i] - g : -inf;
    const double y = std::isfinite(t) ? tracking[i] - t : -inf;
    const double most = std::max(x, y);
    global[i] = most == -inf ? -inf : most + std::log(0.5 * std::exp(x - most) + 0.5 * std::exp(y - most));
  }
}

}  // namespace

FirstSetScoring ParseFirstSetScoring(const std::string& name) {
  if (name == "global") return FirstSetScoring::kGlobal;
  if (name == "tracking") return FirstSetScoring::kTracking;
  if (name == "mixture") return FirstSetScoring::kMixture;
  throw std::invalid_argument("unknown first-set scoring '" + name + "' (expected global, tracking or mixture)");
}

std::string ToString(FirstSetScoring scoring) {
  switch (scoring) {
    case FirstSetScoring::kGlobal: return "global";
    case FirstSetScoring::kTracking: return "tracking";
    case FirstSetScoring::kMixture: return "mixture";
  }
  return "?";
}

StagedSensorModel::StagedSensorModel(std::unique_ptr<SensorModel> global, std::unique_ptr<SensorModel> tracking,
                                     FirstSetScoring first_set)
    : global_model_(std::move(global)), tracking_model_(std::move(tracking)), first_set_(first_set) {
  if (!global_model_ || !tracking_model_) throw std::invalid_argument("a staged sensor model needs both models");
}

std::string StagedSensorModel::name() const { return global_model_->name() + "-then-" + tracking_model_->name(); }

void StagedSensorModel::LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                                       const LaserGeometry& geometry, const BeamSelection& beams,
                                       std::vector<double>& log_likelihoods, SensorUpdateWork& work) {
  Current().LogLikelihoods(particles, scan, geometry, beams, log_likelihoods, work);
}

void StagedSensorModel::SelectionLogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                                                const LaserGeometry& geometry, const BeamSelection& beams,
                                                std::vector<double>& log_likelihoods, SensorUpdateWork& work) {
  if (first_set_ != FirstSetScoring::kTracking)
    global_model_->SelectionLogLikelihoods(particles, scan, geometry, beams, log_likelihoods, work);
  if (first_set_ == FirstSetScoring::kGlobal) return;
  std::vector<double>& tracking = first_set_ == FirstSetScoring::kTracking ? log_likelihoods : tracking_scores_;
  tracking_model_->SelectionLogLikelihoods(particles, scan, geometry, beams, tracking, work);
  if (first_set_ == FirstSetScoring::kMixture) {
    MixPosteriors(log_likelihoods, tracking_scores_);
    tracking_scores_ = std::vector<double>();  // the dense set's scores, freed once used
  }
}

}  // namespace rc
