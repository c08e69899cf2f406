#include "workloads/delibot/staged_sensor_model.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/log_domain.h"

namespace rc {
namespace {

// In place: global[i] = log((exp(global[i] - G) + exp(tracking[i] - T)) / 2)
// with G, T each model's log normalizer; a model whose scores are all -inf
// leaves the other's posterior alone.
void MixPosteriors(std::vector<double>& global, const std::vector<double>& tracking) {
  const double g = LogSumExp(global), t = LogSumExp(tracking);
  const double inf = std::numeric_limits<double>::infinity();
  const double log_half = std::log(0.5);
  for (std::size_t i = 0; i < global.size(); ++i) {
    const double x = std::isfinite(g) ? global[i] - g : -inf;
    const double y = std::isfinite(t) ? tracking[i] - t : -inf;
    global[i] = LogAddExp(x, y) + log_half;
  }
}

constexpr FirstSetScoring kFirstSetScorings[] = {FirstSetScoring::kGlobal, FirstSetScoring::kTracking,
                                                 FirstSetScoring::kMixture};

}  // namespace

FirstSetScoring ParseFirstSetScoring(const std::string& name) {
  for (FirstSetScoring scoring : kFirstSetScorings)
    if (name == ToString(scoring)) return scoring;
  throw std::invalid_argument("unknown first-set scoring '" + name + "' (expected global, tracking or mixture)");
}

std::string ToString(FirstSetScoring scoring) {
  constexpr const char* kNames[] = {"global", "tracking", "mixture"};  // in kFirstSetScorings' order
  return kNames[static_cast<int>(scoring)];
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
  switch (first_set_) {
    case FirstSetScoring::kGlobal:
      global_model_->SelectionLogLikelihoods(particles, scan, geometry, beams, log_likelihoods, work);
      return;
    case FirstSetScoring::kTracking:
      tracking_model_->SelectionLogLikelihoods(particles, scan, geometry, beams, log_likelihoods, work);
      return;
    case FirstSetScoring::kMixture: {
      global_model_->SelectionLogLikelihoods(particles, scan, geometry, beams, log_likelihoods, work);
      std::vector<double> tracking;
      tracking_model_->SelectionLogLikelihoods(particles, scan, geometry, beams, tracking, work);
      MixPosteriors(log_likelihoods, tracking);
      return;
    }
  }
}

}  // namespace rc
