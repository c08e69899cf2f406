#pragma once
// Two sensor models for the two problems a localizer solves (docs/defaults.md).
//
// Global localization chooses among places. There the scan likelihood must
// not be overconfident: a map error that repeats scan after scan (a door
// drawn too narrow, unmapped space behind a wall) must not add up to
// hundreds of nats for a look-alike place, or the true place is resampled
// away and the filter claims the wrong one. The "global" model (the
// likelihood field with nav2's cube sum: a scan moves a weight by a factor
// of about 6 at most) weighs the places while the localizer keeps rivals.
//
// Tracking refines one place. There the likelihood must be sharp and
// unbiased: the beam model tracks simulated traces to about 1 cm where the
// unsigned likelihood field sits 7-10 cm forward of the truth, and its ray
// casts are the work the backends price. The "tracking" model takes over
// once the localizer has found one hypothesis left (BeginTracking).
//
// Both are ordinary SensorModels; this one only forwards to the stage's.
#include <memory>
#include <string>

#include "workloads/delibot/sensor_model.h"

namespace rc {

// Which model scores the dense first update's cut
// (SelectionLogLikelihoods). kGlobal is the design above. kTracking scores
// it with the tracking model, which sees unexpected obstacles (the beam
// model's short readings) but alone claims look-alikes on real maps.
// kMixture draws the cut from the equal mixture of the two models'
// single-scan posteriors (a defensive mixture: each particle's selection
// weight is (p_global / sum p_global + p_tracking / sum p_tracking) / 2),
// so the set keeps the places either model favours and the global stage
// weighs them afterwards. docs/defaults.md, "The first set's cut: a mixture
// of both models".
enum class FirstSetScoring { kGlobal, kTracking, kMixture };
// "global" | "tracking" | "mixture"; throws std::invalid_argument.
FirstSetScoring ParseFirstSetScoring(const std::string& name);
std::string ToString(FirstSetScoring scoring);

class StagedSensorModel final : public SensorModel {
 public:
  // Throws std::invalid_argument if either model is null.
  StagedSensorModel(std::unique_ptr<SensorModel> global, std::unique_ptr<SensorModel> tracking,
                    FirstSetScoring first_set = FirstSetScoring::kGlobal);
  // "<global>-then-<tracking>", e.g. "likelihood-then-beam".
  std::string name() const override;
  void LogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan, const LaserGeometry& geometry,
                      const BeamSelection& beams, std::vector<double>& log_likelihoods,
                      SensorUpdateWork& work) override;
  // The dense first set is a global choice: the global model selects it
  // (or another FirstSetScoring).
  void SelectionLogLikelihoods(const std::vector<Pose2>& particles, const LaserScan& scan,
                               const LaserGeometry& geometry, const BeamSelection& beams,
                               std::vector<double>& log_likelihoods, SensorUpdateWork& work) override;
  bool HasTrackingStage() const override { return true; }
  bool Tracking() const override { return tracking_; }
  void BeginTracking() override { tracking_ = true; }

 private:
  SensorModel& PlaceModel() override { return *global_model_; }
  SensorModel& Current() { return tracking_ ? *tracking_model_ : *global_model_; }

  std::unique_ptr<SensorModel> global_model_;
  std::unique_ptr<SensorModel> tracking_model_;
  FirstSetScoring first_set_;
  bool tracking_ = false;
};

}  // namespace rc
