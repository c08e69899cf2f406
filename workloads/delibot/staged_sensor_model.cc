#include "workloads/delibot/staged_sensor_model.h"

#include <stdexcept>

namespace rc {

FirstSetScoring ParseFirstSetScoring(const std::string& name) {
  if (name == "global") return FirstSetScoring::kGlobal;
  if (name == "tracking") return FirstSetScoring::kTracking;
  throw std::invalid_argument("unknown first-set scoring '" + name + "' (expected global or tracking)");
}

std::string ToString(FirstSetScoring scoring) { return scoring == FirstSetScoring::kGlobal ? "global" : "tracking"; }

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
  SensorModel& model = first_set_ == FirstSetScoring::kGlobal ? *global_model_ : *tracking_model_;
  model.SelectionLogLikelihoods(particles, scan, geometry, beams, log_likelihoods, work);
}

}  // namespace rc
