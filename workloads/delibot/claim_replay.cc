#include "workloads/delibot/claim_replay.h"

#include <cmath>

namespace rc {

bool SelfLocalized(const DelibotRow& row, const DelibotSettings& settings) {
  // hypotheses_alive is 0 when the floor is off.
  return row.mode_weight >= settings.converged_mode_weight && row.consistency >= settings.converged_consistency &&
         row.hypotheses_alive <= 1;
}

bool Jumped(const Pose2& from, const Pose2& to, double jump_threshold_m) {
  return std::hypot(to.x - from.x, to.y - from.y) > jump_threshold_m;
}

bool ClaimReplay::Step(const DelibotRow& row, bool localized) {
  const bool jumped = have_previous_ && Jumped(previous_, row.estimate, jump_threshold_m_);
  have_previous_ = true;
  previous_ = row.estimate;
  if (jumped || row.injected > 0) {
    if (standing_from_ >= 0) ++withdrawn_;
    standing_from_ = -1;
    run_ = 0;
  }
  if (standing_from_ >= 0 || !row.sensor_updated) return false;
  if (!localized) {
    run_ = 0;
    return false;
  }
  if (run_++ == 0) run_start_ = row.iteration;
  return run_ == kSustainRecords;
}

void ClaimReplay::Settle(bool accepted) {
  if (accepted) {
    standing_from_ = run_start_;
    if (first_made_from_ < 0) first_made_from_ = run_start_;
    return;
  }
  ++refused_;
  run_ = 0;
}

}  // namespace rc
