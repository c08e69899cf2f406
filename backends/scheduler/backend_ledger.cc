#include "backends/scheduler/backend_ledger.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace rc {
namespace {

OnlineScheduler MakeOnline(const SchedulerOptions& policy, const std::vector<std::string>& candidates) {
  // The oracle is graded after the run; online it behaves like adaptive so
  // that the timeline still shows what an online policy would have done.
  SchedulerOptions online = policy;
  if (online.kind == SchedulerKind::kOracle) online.kind = SchedulerKind::kAdaptive;
  return OnlineScheduler(online, candidates);
}

// Every modelled backend, robocore first: the adaptive policy starts on the
// first candidate, and before anything is measured the paper's narrative
// (long rays in a localization's first updates) favours the traversal unit.
std::vector<std::string> DefaultCandidates(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  const std::string first = "robocore";
  if (std::find(names.begin(), names.end(), first) != names.end()) out.push_back(first);
  for (const std::string& n : names)
    if (n != first) out.push_back(n);
  return out;
}

// An iteration's modelled cycles on the backend named `name`.
double CyclesOf(const LedgerIteration& it, const std::string& name, const LedgerSummary& s) {
  const auto b = static_cast<std::size_t>(std::find(s.backends.begin(), s.backends.end(), name) - s.backends.begin());
  return static_cast<double>(it.costs.at(b).cycles);
}

// Grades the backends the policy ran (`ran`, per iteration) against the
// oracle's choices in `s`, over the priced iterations (an iteration without
// kernel work costs nothing on any backend).
void GradeAgainstOracle(const std::vector<LedgerIteration>& iterations, const std::vector<std::string>& ran,
                        LedgerSummary& s) {
  std::vector<std::size_t> priced;
  for (std::size_t i = 0; i < iterations.size(); ++i)
    if (iterations[i].priced) priced.push_back(i);
  if (priced.empty()) return;
  std::size_t agree = 0, equivalent = 0;
  for (std::size_t i : priced) {
    agree += ran[i] == s.oracle_choice[i];
    const double mine = CyclesOf(iterations[i], ran[i], s), best = CyclesOf(iterations[i], s.oracle_choice[i], s);
    equivalent += std::abs(mine - best) <= LedgerSummary::kEquivalentPercent / 100.0 * best;
  }
  s.oracle_agreement_percent = 100.0 * static_cast<double>(agree) / static_cast<double>(priced.size());
  s.oracle_equivalent_percent = 100.0 * static_cast<double>(equivalent) / static_cast<double>(priced.size());
  const std::size_t lasting = LedgerSummary::kLastingIterations;
  for (std::size_t j = 1; j < priced.size(); ++j) {
    const std::string& now = s.oracle_choice[priced[j]];
    if (now == s.oracle_choice[priced[j - 1]]) continue;
    std::size_t length = 0;
    while (j + length < priced.size() && s.oracle_choice[priced[j + length]] == now) ++length;
    if (length < lasting) continue;
    ++s.oracle_lasting_changes;
    for (std::size_t k = j; k < j + lasting; ++k)
      if (ran[priced[k]] == now) {
        ++s.oracle_lasting_changes_followed;
        break;
      }
  }
}

}  // namespace

BackendLedger::BackendLedger(const BackendParameters& params, LedgerOptions options)
    : options_(std::move(options)),
      params_(params),
      online_(MakeOnline(options_.policy.kind == SchedulerKind::kStatic ? options_.policy : SchedulerOptions{},
                         Backend::ModelledNames())) {
  for (const std::string& name : Backend::ModelledNames()) {
    backends_.push_back(Backend::Create(name, params));
    backend_ptrs_.push_back(backends_.back().get());
    names_.push_back(name);
  }
  candidates_ = options_.policy.candidates.empty() ? DefaultCandidates(names_) : options_.policy.candidates;
  std::vector<const std::string*> named = {&options_.policy.static_backend, &options_.policy.high_backend,
                                           &options_.policy.low_backend};
  for (const std::string& c : candidates_) named.push_back(&c);
  for (const std::string* n : named)
    if (std::find(names_.begin(), names_.end(), *n) == names_.end())
      throw std::invalid_argument("the scheduler names '" + *n + "', which has no cost model");
  for (const std::string& c : candidates_) candidate_index_.push_back(IndexOf(c));
  if (!(options_.switch_cost_cycles >= 0.0)) throw std::invalid_argument("the switch cost must be >= 0 cycles");
  switch_cost_cycles_ = options_.switch_cost_cycles;
  options_.policy.switch_cost_cycles = switch_cost_cycles_;
  threshold_has_crossing_ = options_.threshold_overridden;
  online_ = MakeOnline(options_.policy, candidates_);
}

std::size_t BackendLedger::IndexOf(const std::string& name) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) throw std::invalid_argument("no backend named '" + name + "'");
  return static_cast<std::size_t>(it - names_.begin());
}

AddressSample BackendLedger::RecordSample() const {
  AddressSample sample;
  sample.warp_size = params_.gpu.warp_size;
  sample.warps_per_block = params_.gpu.warps_per_block;
  sample.sms = params_.gpu.sms;
  sample.sector_bytes = params_.gpu.sector_bytes;
  sample.sampled_sms = options_.replay_sms;
  sample.block_stride = options_.replay_block_stride;
  return sample;
}

std::size_t BackendLedger::StartProbeQueries(std::size_t first_batch_queries) {
  return std::min(first_batch_queries, kStartProbeMaxQueries);
}

void BackendLedger::Prepare(const KernelRecord& template_record, std::size_t queries_per_batch, std::uint32_t max_nodes,
                            const KernelRecord* start_probe) {
  if (prepared_) return;
  prepared_ = true;
  if (options_.policy.kind == SchedulerKind::kThreshold && !options_.threshold_overridden) {
    const CrossoverResult crossing = DeriveCrossoverThreshold(
        *backends_[IndexOf(options_.policy.high_backend)], *backends_[IndexOf(options_.policy.low_backend)],
        template_record, queries_per_batch, max_nodes, RecordSample());
    options_.policy.threshold_nodes_per_query = crossing.threshold_nodes_per_query;
    threshold_has_crossing_ = crossing.has_crossing;
  } else if (options_.policy.kind == SchedulerKind::kAdaptive || options_.policy.kind == SchedulerKind::kOracle) {
    std::vector<const Backend*> candidates;
    for (std::size_t k : candidate_index_) candidates.push_back(backend_ptrs_[k]);
    const std::vector<BatchCost> costs =
        start_probe && start_probe->query_count() > 0
            ? PriceAll(candidates, *start_probe)
            : PriceAll(candidates, MakeSpreadProbe(template_record, queries_per_batch, max_nodes, RecordSample()));
    std::size_t best = 0;
    for (std::size_t k = 1; k < costs.size(); ++k)
      if (costs[k].cycles < costs[best].cycles) best = k;
    options_.policy.initial_backend = candidates_[best];
  }
  online_ = MakeOnline(options_.policy, candidates_);
}

const std::string& BackendLedger::BeginIteration() {
  pending_backend_ = online_.Choose(last_);
  return pending_backend_;
}

void BackendLedger::AddLaunch(const KernelRecord& record) {
  if (record.query_count() == 0) return;
  // A threshold not derived yet is derived from the first priced launch.
  // No counter was seen before it, so the policy is still on its initial
  // choice, where the fresh one Prepare makes continues. (The adaptive
  // policy's first choice was made already: it stays.)
  if (!prepared_ && options_.policy.kind == SchedulerKind::kThreshold) Prepare(record, record.query_count());
  any_sampled_ = any_sampled_ || record.sampled();
  std::vector<BatchCost> costs = PriceAll(backend_ptrs_, record);
  if (open_costs_.empty())
    open_costs_ = std::move(costs);
  else
    for (std::size_t b = 0; b < costs.size(); ++b) open_costs_[b] += costs[b];
  open_queries_ += record.query_count();
  open_nodes_ += record.total_nodes();
  ++open_launches_;
  ++launches_;
}

void BackendLedger::AddLaunchesLike(const EstimatedLaunches& estimated) {
  if (estimated.count == 0) return;
  if (estimated.like == 0 || estimated.like != open_launches_)
    throw std::logic_error("BackendLedger::AddLaunchesLike: " + std::to_string(estimated.like) +
                           " recorded launches named, " + std::to_string(open_launches_) + " in the iteration");
  const double scale = static_cast<double>(estimated.count) / static_cast<double>(estimated.like);
  for (BatchCost& cost : open_costs_) {
    BatchCost more = cost.ScaledBy(scale);
    more.queries = estimated.queries;
    more.nodes = estimated.nodes;
    cost += more;
  }
  open_queries_ += estimated.queries;
  open_nodes_ += estimated.nodes;
  open_launches_ += estimated.count;
  launches_ += static_cast<long>(estimated.count);
  estimated_launches_ += static_cast<long>(estimated.count);
}

const LedgerIteration& BackendLedger::EndIteration(const KernelRecord* record) {
  LedgerIteration it;
  it.backend = pending_backend_.empty() ? online_.current() : pending_backend_;
  it.nodes_per_query_prev = last_.nodes_per_query;
  it.switched = !previous_backend_.empty() && it.backend != previous_backend_;
  if (record) AddLaunch(*record);
  last_ = IterationObservation{};
  if (open_queries_ > 0) {
    it.priced = true;
    it.costs = std::move(open_costs_);
    it.nodes_per_query = static_cast<double>(open_nodes_) / static_cast<double>(open_queries_);
    const BatchCost& chosen = it.costs[IndexOf(it.backend)];
    it.chosen_cycles = static_cast<double>(chosen.cycles);
    it.chosen_energy_j = chosen.energy_joules;
    last_.ran = true;
    last_.nodes_per_query = it.nodes_per_query;
    for (std::size_t k : candidate_index_) last_.candidate_cycles.push_back(static_cast<double>(it.costs[k].cycles));
  }
  open_costs_.clear();
  open_queries_ = open_nodes_ = 0;
  open_launches_ = 0;
  if (it.switched) it.chosen_cycles += switch_cost_cycles_;
  if (options_.policy.kind == SchedulerKind::kThreshold) it.threshold = options_.policy.threshold_nodes_per_query;
  previous_backend_ = it.backend;
  iterations_.push_back(std::move(it));
  return iterations_.back();
}

std::string DescribeMemoryReplay(int replay_sms, int replay_block_stride) {
  if (replay_sms <= 0) return "memory replayed on every SM";
  return fmt::format("memory replayed on {} SM(s){}, the rest estimated", replay_sms,
                     replay_block_stride > 1 ? fmt::format(", 1 block in {}", replay_block_stride) : "");
}

LedgerSummary BackendLedger::Finish() const {
  LedgerSummary s;
  s.backends = names_;
  s.static_total_cycles.assign(names_.size(), 0.0);
  s.switch_cost_cycles = switch_cost_cycles_;
  s.replay_sms = any_sampled_ ? options_.replay_sms : 0;
  s.replay_block_stride = any_sampled_ ? options_.replay_block_stride : 1;
  s.launches = launches_;
  s.estimated_launches = estimated_launches_;
  if (options_.policy.kind == SchedulerKind::kThreshold) s.threshold = options_.policy.threshold_nodes_per_query;
  s.threshold_has_crossing = threshold_has_crossing_;
  s.oracle_candidates = candidates_;
  std::vector<std::vector<double>> candidate_cycles;
  for (const LedgerIteration& it : iterations_) {
    std::vector<double> row(candidate_index_.size(), 0.0);
    if (it.priced) {
      for (std::size_t b = 0; b < names_.size(); ++b) s.static_total_cycles[b] += it.costs[b].cycles;
      for (std::size_t k = 0; k < candidate_index_.size(); ++k) row[k] = it.costs[candidate_index_[k]].cycles;
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
  std::vector<std::string> ran;  // per iteration, the backend the policy ran
  for (const LedgerIteration& it : iterations_) ran.push_back(it.backend);
  if (options_.policy.kind == SchedulerKind::kOracle) {
    // The oracle policy's own total and choices are the oracle's.
    s.policy_total_cycles = s.oracle_total_cycles;
    s.switches = 0;
    for (std::size_t i = 1; i < oracle.size(); ++i) s.switches += oracle[i] != oracle[i - 1];
    ran = s.oracle_choice;
  }
  GradeAgainstOracle(iterations_, ran, s);
  const auto best = std::min_element(s.static_total_cycles.begin(), s.static_total_cycles.end());
  if (best != s.static_total_cycles.end())
    s.best_static = names_[static_cast<std::size_t>(best - s.static_total_cycles.begin())];
  s.gap_to_oracle_percent =
      s.oracle_total_cycles > 0 ? 100.0 * (s.policy_total_cycles - s.oracle_total_cycles) / s.oracle_total_cycles : 0.0;
  return s;
}

}  // namespace rc
