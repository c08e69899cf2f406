#pragma once
// The ground-truth-free claim of a DeliBot run, replayed record by record:
// the one definition that both the run (which audits a claim as it falls
// due, claim_audit.h) and the summary (which reports the claims) follow.
#include "workloads/delibot/delibot_run.h"

namespace rc {

// Consecutive localized sensor updates after which the filter claims to be
// localized (and the summary's convergence tests are sustained).
inline constexpr int kSustainRecords = 10;

// The filter's own test of one record: the estimate's mode holds
// converged_mode_weight, converged_consistency of the beams agree with the
// map there, and (with the hypothesis floor) no rival hypothesis is alive.
bool SelfLocalized(const DelibotRow& row, const DelibotSettings& settings);

// The estimate moved farther than jump_threshold_m between two records: the
// filter switched hypotheses (a robot does not teleport).
bool Jumped(const Pose2& from, const Pose2& to, double jump_threshold_m);

// A claim is due after kSustainRecords consecutive localized sensor updates
// and stands until the first jump (> jump_threshold_m between two records)
// or injection after it, which withdraws it. A localized update that merely
// dips below a threshold breaks a run being built but withdraws no claim:
// one scan's consistency is noisy (a person, a poorly mapped door). A due
// claim that its audit refuses is not made, and a new one needs
// kSustainRecords more localized updates.
class ClaimReplay {
 public:
  explicit ClaimReplay(double jump_threshold_m) : jump_threshold_m_(jump_threshold_m) {}
  // Feeds the next record; true when a claim falls due at it. The caller
  // then calls Settle before the next record.
  bool Step(const DelibotRow& row, bool localized);
  // Makes the due claim (accepted) or refuses it.
  void Settle(bool accepted);
  // The record from which the standing claim was made (-1: none stands).
  long standing_from() const { return standing_from_; }
  // The record from which the first claim was made (-1: none was).
  long first_made_from() const { return first_made_from_; }
  long withdrawn() const { return withdrawn_; }
  long refused() const { return refused_; }

 private:
  double jump_threshold_m_;
  bool have_previous_ = false;
  Pose2 previous_;
  int run_ = 0;
  long run_start_ = -1;
  long standing_from_ = -1;
  long first_made_from_ = -1;
  long withdrawn_ = 0;
  long refused_ = 0;
};

}  // namespace rc
