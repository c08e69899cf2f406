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
#include "common/parameter_spec.h"
#include "robocore/address_sample.h"
#include "robocore/launch_sample.h"

namespace rc {

struct LedgerOptions {
  SchedulerOptions policy;
  // Threshold policy: the threshold was given (else derived from the cost
  // models before the first iteration).
  bool threshold_overridden = false;
  // Cycles a change of backend adds to the iteration that changes (core
  // cycles, >= 0). Default 0, an assumption: every iteration launches its
  // kernel anyway, and each backend's cycles already include its launch and,
  // on the RT units, the program and decode configuration at every launch
  // (backends/README.md), so a change of backend adds nothing of its own.
  // A positive value models a cost beyond that (e.g. one kernel launch,
  // 5000 cycles, if a switch drained the GPU).
  double switch_cost_cycles = 0.0;
  // SMs whose memory traffic is replayed exactly (backends/memory_replay.h);
  // the others' is estimated from them. 0 (or >= the GPU's SMs): every SM,
  // exact. Recording keeps only the replayed SMs' addresses
  // (RecordSample()).
  int replay_sms = 0;
  // Of each replayed SM's blocks, every replay_block_stride-th is replayed
  // (AddressSample::block_stride; the others are estimated from them).
  // Applies only when SMs are sampled (0 < replay_sms < the GPU's SMs).
  int replay_block_stride = 1;
  // Full launches of a split batch that are recorded and priced, at most
  // (robocore/launch_sample.h); the workload casts the others without a
  // record and AddLaunchesLike prices them. 0: every launch.
  int priced_launches = kPricedLaunchesPerBatch;
};

struct LedgerIteration {
  bool priced = false;                                          // false: no kernel work this iteration
  std::string backend;                                          // the one the policy chose
  double nodes_per_query = -1.0;                                // this iteration (-1 if none)
  double nodes_per_query_prev = -1.0;                           // what the decision saw
  double threshold = std::numeric_limits<double>::quiet_NaN();  // threshold policy only
  bool switched = false;
  std::vector<BatchCost> costs;  // one per ledger backend (empty if !priced)
  double chosen_cycles = 0.0;    // incl. a switch cost if switched
  double chosen_energy_j = 0.0;
};

// How a priced run's memory was replayed, for its summary: "memory replayed
// on every SM" (replay_sms 0), or on the sampled SMs (and blocks), "the rest
// estimated".
std::string DescribeMemoryReplay(int replay_sms, int replay_block_stride);

struct LedgerSummary {
  std::vector<std::string> backends;
  std::vector<double> static_total_cycles;  // per backend
  double policy_total_cycles = 0.0;         // the chosen policy, switches included
  double oracle_total_cycles = 0.0;         // hindsight over the candidates
  std::vector<std::string> oracle_candidates;
  long switches = 0;
  double switch_cost_cycles = 0.0;
  double threshold = std::numeric_limits<double>::quiet_NaN();
  bool threshold_has_crossing = false;
  std::string best_static;
  double gap_to_oracle_percent = 0.0;  // (policy - oracle) / oracle
  // Priced iterations on which the policy ran the backend the oracle chose
  // (percent; NaN with none priced).
  double oracle_agreement_percent = std::numeric_limits<double>::quiet_NaN();
  // The same, counting as agreement a backend whose cycles in that
  // iteration are within kEquivalentPercent of the oracle's choice: near-tied
  // backends (TTA+ with and without conditional return differ by a fraction
  // of a percent on ray casts) make the oracle's pick among them arbitrary,
  // and choosing either is the same decision. 1%: below the sampled
  // replay's stated error (3.5%, tests/backends/sampled_pricing_test.cc).
  static constexpr double kEquivalentPercent = 1.0;
  double oracle_equivalent_percent = std::numeric_limits<double>::quiet_NaN();
  // The oracle's changes of backend that last at least kLastingIterations
  // priced iterations, and how many of them the policy followed (it ran the
  // oracle's new backend within kLastingIterations of the change).
  static constexpr int kLastingIterations = 5;
  long oracle_lasting_changes = 0;
  long oracle_lasting_changes_followed = 0;
  std::vector<double> oracle_cumulative_cycles;  // per iteration
  std::vector<std::string> oracle_choice;        // per iteration
  int replay_sms = 0;                            // SMs replayed exactly when a priced record was sampled; 0 = every SM
  int replay_block_stride = 1;                   // of a replayed SM's blocks, every this-many-th replayed
  long launches = 0;                             // launches priced (recorded or estimated)
  long estimated_launches = 0;                   // of them, priced as the mean of recorded ones (AddLaunchesLike)
};

// The most queries a start probe (BackendLedger::Prepare) holds. A probe
// as large as the first batch prices it best (the batch's size moves the
// CUDA cores' cost against the RT units' by up to 2x, docs/scheduling.md),
// but costs what casting and pricing that batch costs, and a global
// localization's first batch can hold 10^8 rays. 2^16 queries are 8 full
// waves of the default GPU (8 SMs x 32 warps x 32 threads). Measured on the
// hall (docs/scheduling.md, "Where to start"): a DeliBot probe of 2^16 rays
// ranks the backends as one of the first update's 300,000 does, each
// backend's cycles relative to the cheapest within 7% of their value
// there, and costs 0.13-0.23 s on the host.
inline constexpr std::size_t kStartProbeMaxQueries = std::size_t{1} << 16;
inline constexpr ParameterSpec kStartProbeMaxQueriesSpec{
    "queries", 1024, 1 << 24,
    "own measurement: hall scene, DeliBot probes of 16,380 to 300,000 rays (docs/scheduling.md, \"Where to start\")"};
static_assert(kStartProbeMaxQueriesSpec.min <= kStartProbeMaxQueries &&
              kStartProbeMaxQueries <= kStartProbeMaxQueriesSpec.max);

class BackendLedger {
 public:
  BackendLedger(const BackendParameters& params, LedgerOptions options);
  const std::vector<std::string>& backend_names() const { return names_; }
  const std::vector<std::string>& candidates() const { return candidates_; }
  std::size_t IndexOf(const std::string& name) const;
  // Whose addresses a recorder must keep for this ledger's replay.
  AddressSample RecordSample() const;
  // Derives, before the first iteration, what the online policy needs from
  // the cost models, given a record with the workload's program and memory
  // layout (its fetches do not matter), the workload's batch size, and the
  // most nodes a query of the workload can fetch:
  //   threshold  the crossover threshold (crossover_threshold.h); without
  //              this call it is derived at the first priced iteration
  //              instead (max_nodes kDefaultMaxNodesPerQuery);
  //   adaptive   where to start (nothing has been measured yet): the
  //              candidate cheapest on `start_probe`, a batch the workload
  //              recorded before its first iteration from what it knows in
  //              advance, drawn as its first batch will be (DeliBot:
  //              workloads/delibot/start_probe.h), at most
  //              StartProbeQueries() queries; without one, on
  //              MakeSpreadProbe(template_record, queries_per_batch,
  //              max_nodes), every length from 1 to max_nodes equally
  //              often. Without this call it starts on the first candidate.
  void Prepare(const KernelRecord& template_record, std::size_t queries_per_batch,
               std::uint32_t max_nodes = kDefaultMaxNodesPerQuery, const KernelRecord* start_probe = nullptr);
  // Whether Prepare chooses where to start from a probe (the adaptive
  // policy, and the oracle's online stand-in): a workload need not record
  // a start probe otherwise.
  bool ChoosesStart() const {
    return options_.policy.kind == SchedulerKind::kAdaptive || options_.policy.kind == SchedulerKind::kOracle;
  }
  // The queries a start probe for a first batch of `first_batch_queries`
  // needs: all of them, up to kStartProbeMaxQueries.
  static std::size_t StartProbeQueries(std::size_t first_batch_queries);
  // The backend for the coming iteration, from the previous iteration's
  // counter.
  const std::string& BeginIteration();
  // Prices the iteration's record on every backend (null: nothing ran).
  const LedgerIteration& EndIteration(const KernelRecord* record);
  // An iteration of several kernel launches (CarriBot: one per A*
  // expansion): prices one launch on every backend now and adds its cost to
  // the iteration in progress, which EndIteration closes with the sums.
  void AddLaunch(const KernelRecord& record);
  // Launches a launch sample left unrecorded: adds `estimated.count`
  // launches, each priced as the mean of the launches added so far to the
  // iteration in progress, which must be `estimated.like` (the batch's
  // recorded launches), with the exact queries and nodes given. Every other
  // count and time is an estimate; the summary says how many launches were.
  void AddLaunchesLike(const EstimatedLaunches& estimated);
  const std::vector<LedgerIteration>& iterations() const { return iterations_; }
  LedgerSummary Finish() const;
  const SchedulerOptions& policy() const { return options_.policy; }
  const LedgerOptions& options() const { return options_; }

 private:
  LedgerOptions options_;
  BackendParameters params_;
  std::vector<std::unique_ptr<Backend>> backends_;
  std::vector<const Backend*> backend_ptrs_;
  std::vector<std::string> names_;
  std::vector<std::string> candidates_;
  std::vector<std::size_t> candidate_index_;
  OnlineScheduler online_;
  double switch_cost_cycles_ = 0.0;
  bool prepared_ = false;
  bool threshold_has_crossing_ = false;
  IterationObservation last_;
  std::string pending_backend_;
  std::string previous_backend_;
  std::vector<LedgerIteration> iterations_;
  std::vector<BatchCost> open_costs_;  // launches added to the iteration in progress
  std::uint64_t open_queries_ = 0, open_nodes_ = 0;
  std::size_t open_launches_ = 0;  // launches added to the iteration in progress
  long launches_ = 0, estimated_launches_ = 0;
  bool any_sampled_ = false;  // a priced record kept a sample of its addresses
};

}  // namespace rc
