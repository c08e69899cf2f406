#include "backends/scheduler/backend_ledger.h"

#include <algorithm>
#include <stdexcept>

namespace rc {
namespace {

OnlineScheduler MakeOnline(const SchedulerOptions& policy) {
  // The oracle is graded after the run; online it behaves like adaptive so
  // that the timeline still shows what an online policy would have done.
  SchedulerOptions online = policy;
  if (online.kind == SchedulerKind::kOracle) online.kind = SchedulerKind::kAdaptive;
  return OnlineScheduler(online);
}

// Sums two launches' costs. SIMT efficiency is active lanes over issued
// lanes, so the sum is the issued-instruction-weighted mean.
void AddCost(BatchCost& total, const BatchCost& more) {
  const double wa = static_cast<double>(total.warp_instructions), wb = static_cast<double>(more.warp_instructions);
  if (wa + wb > 0) total.simt_efficiency = (total.simt_efficiency * wa + more.simt_efficiency * wb) / (wa + wb);
  total.host_seconds += more.host_seconds;
  total.queries += more.queries;
  total.nodes += more.nodes;
  total.cycles += more.cycles;
  total.launch_cycles += more.launch_cycles;
  total.seconds += more.seconds;
  total.energy_joules += more.energy_joules;
  total.memory.sector_requests += more.memory.sector_requests;
  total.memory.l1_hits += more.memory.l1_hits;
  total.memory.l2_accesses += more.memory.l2_accesses;
  total.memory.l2_hits += more.memory.l2_hits;
  total.memory.dram_accesses += more.memory.dram_accesses;
  for (std::size_t k = 0; k < total.micro_ops.size(); ++k) total.micro_ops[k] += more.micro_ops[k];
  total.predicated_off_micro_ops += more.predicated_off_micro_ops;
  total.interconnect_hops += more.interconnect_hops;
  total.ctrl_exits += more.ctrl_exits;
  total.warp_instructions += more.warp_instructions;
  total.thread_instructions += more.thread_instructions;
  total.nodes_counted += more.nodes_counted;
}

}  // namespace

BackendLedger::BackendLedger(const BackendParameters& params, LedgerOptions options)
    : options_(std::move(options)), online_(MakeOnline(options_.policy)) {
  for (const std::string& name : Backend::ModelledNames()) {
    backends_.push_back(Backend::Create(name, params));
    backend_ptrs_.push_back(backends_.back().get());
    names_.push_back(name);
  }
  for (const std::string* n : {&options_.policy.static_backend, &options_.policy.high_backend,
                               &options_.policy.low_backend})
    if (std::find(names_.begin(), names_.end(), *n) == names_.end())
      throw std::invalid_argument("the scheduler names '" + *n + "', which has no cost model");
  switch_cost_cycles_ = options_.switch_cost_cycles >= 0.0 ? options_.switch_cost_cycles
                                                           : static_cast<double>(params.gpu.kernel_launch_cycles);
  options_.policy.switch_cost_cycles = switch_cost_cycles_;
  threshold_known_ = options_.threshold_overridden || options_.policy.kind == SchedulerKind::kStatic;
  threshold_has_crossing_ = options_.threshold_overridden;
  online_ = MakeOnline(options_.policy);
}

std::size_t BackendLedger::IndexOf(const std::string& name) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) throw std::invalid_argument("no backend named '" + name + "'");
  return static_cast<std::size_t>(it - names_.begin());
}

void BackendLedger::PrepareThreshold(const KernelRecord& template_record, std::size_t queries_per_batch) {
  if (threshold_known_) return;
  const CrossoverResult crossing =
      DeriveCrossoverThreshold(*backends_[IndexOf(options_.policy.high_backend)],
                               *backends_[IndexOf(options_.policy.low_backend)], template_record, queries_per_batch);
  options_.policy.threshold_nodes_per_query = crossing.threshold_nodes_per_query;
  threshold_has_crossing_ = crossing.has_crossing;
  threshold_known_ = true;
  online_ = MakeOnline(options_.policy);
}

const std::string& BackendLedger::BeginIteration() {
  pending_backend_ = online_.Choose(last_nodes_per_query_);
  return pending_backend_;
}

void BackendLedger::AddLaunch(const KernelRecord& record) {
  if (record.query_count() == 0) return;
  // The first priced launch derives the crossover for batches like this
  // one. No counter was seen before it, so the policy is still on its
  // initial choice and the fresh one PrepareThreshold makes continues there.
  PrepareThreshold(record, record.query_count());
  std::vector<BatchCost> costs = PriceAll(backend_ptrs_, record);
  if (open_costs_.empty()) open_costs_ = std::move(costs);
  else
    for (std::size_t b = 0; b < costs.size(); ++b) AddCost(open_costs_[b], costs[b]);
  open_queries_ += record.query_count();
  open_nodes_ += record.total_nodes();
}

const LedgerIteration& BackendLedger::EndIteration(const KernelRecord* record) {
  LedgerIteration it;
  it.backend = pending_backend_.empty() ? online_.current() : pending_backend_;
  it.nodes_per_query_prev = last_nodes_per_query_;
  it.switched = !previous_backend_.empty() && it.backend != previous_backend_;
  if (record) AddLaunch(*record);
  if (open_queries_ > 0) {
    it.priced = true;
    it.costs = std::move(open_costs_);
    it.nodes_per_query = static_cast<double>(open_nodes_) / static_cast<double>(open_queries_);
    const BatchCost& chosen = it.costs[IndexOf(it.backend)];
    it.chosen_cycles = static_cast<double>(chosen.cycles);
    it.chosen_energy_j = chosen.energy_joules;
    last_nodes_per_query_ = it.nodes_per_query;
  } else {
    last_nodes_per_query_ = -1.0;
  }
  open_costs_.clear();
  open_queries_ = open_nodes_ = 0;
  if (it.switched) it.chosen_cycles += switch_cost_cycles_;
  if (options_.policy.kind != SchedulerKind::kStatic) it.threshold = options_.policy.threshold_nodes_per_query;
  previous_backend_ = it.backend;
  iterations_.push_back(std::move(it));
  return iterations_.back();
}

std::vector<std::string> BackendLedger::OracleCandidates() const {
  if (options_.policy.kind == SchedulerKind::kStatic) return names_;
  return {options_.policy.low_backend, options_.policy.high_backend};
}

LedgerSummary BackendLedger::Finish() const {
  LedgerSummary s;
  s.backends = names_;
  s.static_total_cycles.assign(names_.size(), 0.0);
  s.switch_cost_cycles = switch_cost_cycles_;
  s.threshold = options_.policy.kind == SchedulerKind::kStatic ? s.threshold : options_.policy.threshold_nodes_per_query;
  s.threshold_has_crossing = threshold_has_crossing_;
  s.oracle_candidates = OracleCandidates();
  std::vector<std::size_t> candidate_index;
  for (const auto& c : s.oracle_candidates) candidate_index.push_back(IndexOf(c));
  std::vector<std::vector<double>> candidate_cycles;
  for (const LedgerIteration& it : iterations_) {
    std::vector<double> row(candidate_index.size(), 0.0);
    if (it.priced) {
      for (std::size_t b = 0; b < names_.size(); ++b) s.static_total_cycles[b] += it.costs[b].cycles;
      for (std::size_t k = 0; k < candidate_index.size(); ++k) row[k] = it.costs[candidate_index[k]].cycles;
    }
    candidate_cycles.push_back(row);
    s.policy_total_cycles += it.chosen_cycles;
    s.switches += it.switched;
  }
  const std::vector<std::size_t> oracle = OracleSchedule(candidate_cycles, switch_cost_cycles_);
  double cumulative = 0.0;
  for (std::size_t i = 0; i < oracle.size(); ++i) {
    cumulative += candidate_cycles[i][oracle[i]];
    if (i > 0 && oracle[i] != oracle[i - 1]) cumulative += switch_cost_cycles_;
    s.oracle_cumulative_cycles.push_back(cumulative);
    s.oracle_choice.push_back(s.oracle_candidates[oracle[i]]);
  }
  s.oracle_total_cycles = cumulative;
  if (options_.policy.kind == SchedulerKind::kOracle) {
    // The oracle policy's own total is the oracle's.
    s.policy_total_cycles = s.oracle_total_cycles;
    s.switches = 0;
    for (std::size_t i = 1; i < oracle.size(); ++i) s.switches += oracle[i] != oracle[i - 1];
  }
  const auto best = std::min_element(s.static_total_cycles.begin(), s.static_total_cycles.end());
  if (best != s.static_total_cycles.end()) s.best_static = names_[static_cast<std::size_t>(best - s.static_total_cycles.begin())];
  s.gap_to_oracle_percent =
      s.oracle_total_cycles > 0 ? 100.0 * (s.policy_total_cycles - s.oracle_total_cycles) / s.oracle_total_cycles : 0.0;
  return s;
}

}  // namespace rc
