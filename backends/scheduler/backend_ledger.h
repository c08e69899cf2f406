#pragma once
// Shadow costing of a workload, iteration by iteration: every modelled
// backend prices every iteration's recorded kernel batch (run once, price
// many times), an online policy picks the backend that "ran", and at the end
// the hindsight oracle and the totals of every static choice grade it.
// Workload-agnostic: DeliBot, CarriBot and MoveBot feed it one record (or
// none) per iteration.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "backends/scheduler/backend_scheduler.h"
#include "backends/scheduler/crossover_threshold.h"

namespace rc {

struct LedgerOptions {
  SchedulerOptions policy;
  // Adaptive threshold: derived from the cost models when not set.
  bool threshold_overridden = false;
  // Switch cost (core cycles); negative: one kernel launch of the GPU model
  // (reconfiguring which unit runs the kernel costs at least a relaunch).
  double switch_cost_cycles = -1.0;
};

struct LedgerIteration {
  bool priced = false;                     // false: no kernel work this iteration
  std::string backend;                     // the one the policy chose
  double nodes_per_query = -1.0;           // this iteration (-1 if none)
  double nodes_per_query_prev = -1.0;      // what the decision saw
  double threshold = std::numeric_limits<double>::quiet_NaN();  // adaptive only
  bool switched = false;
  std::vector<BatchCost> costs;            // one per ledger backend (empty if !priced)
  double chosen_cycles = 0.0;              // incl. a switch cost if switched
  double chosen_energy_j = 0.0;
};

struct LedgerSummary {
  std::vector<std::string> backends;
  std::vector<double> static_total_cycles;   // per backend
  double policy_total_cycles = 0.0;          // the chosen policy, switches included
  double oracle_total_cycles = 0.0;          // over {low, high} for adaptive/oracle, else all
  std::vector<std::string> oracle_candidates;
  long switches = 0;
  double switch_cost_cycles = 0.0;
  double threshold = std::numeric_limits<double>::quiet_NaN();
  bool threshold_has_crossing = false;
  std::string best_static;
  double gap_to_oracle_percent = 0.0;        // (policy - oracle) / oracle
  std::vector<double> oracle_cumulative_cycles;  // per iteration
  std::vector<std::string> oracle_choice;        // per iteration
};

class BackendLedger {
 public:
  BackendLedger(const BackendParameters& params, LedgerOptions options);
  const std::vector<std::string>& backend_names() const { return names_; }
  std::size_t IndexOf(const std::string& name) const;
  // Derives the adaptive threshold before the first iteration from a record
  // with the workload's program and memory layout (its fetches do not
  // matter) and the workload's batch size. Without this call, the threshold
  // is derived at the first priced iteration instead.
  void PrepareThreshold(const KernelRecord& template_record, std::size_t queries_per_batch);
  // The backend for the coming iteration, from the previous iteration's
  // counter.
  const std::string& BeginIteration();
  // Prices the iteration's record on every backend (null: nothing ran).
  const LedgerIteration& EndIteration(const KernelRecord* record);
  // An iteration of several kernel launches (CarriBot: one per A*
  // expansion): prices one launch on every backend now and adds its cost to
  // the iteration in progress, which EndIteration closes with the sums.
  void AddLaunch(const KernelRecord& record);
  const std::vector<LedgerIteration>& iterations() const { return iterations_; }
  LedgerSummary Finish() const;
  const SchedulerOptions& policy() const { return options_.policy; }

 private:
  std::vector<std::string> OracleCandidates() const;

  LedgerOptions options_;
  std::vector<std::unique_ptr<Backend>> backends_;
  std::vector<const Backend*> backend_ptrs_;
  std::vector<std::string> names_;
  OnlineScheduler online_;
  double switch_cost_cycles_ = 0.0;
  bool threshold_known_ = false;
  bool threshold_has_crossing_ = false;
  double last_nodes_per_query_ = -1.0;
  std::string pending_backend_;
  std::string previous_backend_;
  std::vector<LedgerIteration> iterations_;
  std::vector<BatchCost> open_costs_;  // launches added to the iteration in progress
  std::uint64_t open_queries_ = 0, open_nodes_ = 0;
};

}  // namespace rc
