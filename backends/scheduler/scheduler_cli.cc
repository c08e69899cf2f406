#include "backends/scheduler/scheduler_cli.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "backends/backend.h"
#include "common/input_error.h"

namespace rc {

void AddSchedulerOptions(CLI::App& command, SchedulerCli& cli, const std::string& counter) {
  std::string names;
  for (const std::string& n : Backend::ModelledNames()) names += (names.empty() ? "" : "|") + n;
  command
      .add_option("--backend", cli.policy,
                  "Backend that runs each iteration: adaptive (predicts each candidate's cycles from the "
                  "previous iteration's) | threshold (the paper's: " +
                      counter +
                      " against a threshold) | "
                      "oracle (hindsight) | static:<" +
                      names + "> (every backend is priced regardless)")
      ->capture_default_str();
  command.add_option("--candidates", cli.candidates,
                     "Backends the adaptive policy and the oracle choose among, comma-separated (default: all)");
  command.add_option("--threshold", cli.threshold,
                     "Threshold policy's switch point (" + counter + "); default: the cost models' crossover");
  command
      .add_option("--hysteresis", cli.hysteresis, "Threshold policy's margin around the threshold (" + counter + ")")
      ->capture_default_str();
  command
      .add_option("--switch-cost", cli.switch_cost,
                  "Cycles a change of backend adds beyond the launch every iteration pays anyway (core cycles, "
                  ">= 0; see backends/scheduler/backend_ledger.h)")
      ->capture_default_str();
  command
      .add_option("--replay-sms", cli.replay_sms,
                  "SMs whose memory traffic is replayed (count; the others are estimated from them; "
                  "0 = every SM, exact)")
      ->capture_default_str();
  command
      .add_option("--replay-block-stride", cli.replay_block_stride,
                  "Of each replayed SM's blocks, every Nth is replayed, the others estimated from them (count, >= 1; "
                  "1 = all of them; applies while --replay-sms samples)")
      ->capture_default_str();
  command
      .add_option("--priced-launches", cli.priced_launches,
                  "Of a batch split into launches (DeliBot: above 2^20 rays), the full launches recorded and priced, "
                  "spread evenly; the others are priced as their mean (count; 0 = every launch, exact)")
      ->capture_default_str();
  command.add_option(
      "--backend-params", cli.backend_params,
      "A named preset (artifact: the RoboGPU artifact's configuration, backends/presets/artifact.json) or a JSON "
      "file overriding backend cost parameters (see rcbench backends)");
  command.add_flag("--no-pricing", cli.no_pricing, "Do not price the kernels on the modelled backends");
}

LedgerOptions ToLedgerOptions(const SchedulerCli& cli) {
  LedgerOptions options;
  const std::vector<std::string> names = Backend::ModelledNames();
  try {
    options.policy = ParseSchedulerPolicy(cli.policy, names);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--backend: ") + e.what());
  }
  try {
    if (!cli.candidates.empty()) options.policy.candidates = ParseCandidates(cli.candidates, names);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--candidates: ") + e.what());
  }
  if (!(cli.hysteresis >= 0.0)) throw UsageError("--hysteresis must be >= 0");
  if (!(cli.switch_cost >= 0.0 && std::isfinite(cli.switch_cost)))
    throw UsageError("--switch-cost must be a finite number of cycles >= 0");
  auto check_range = [](const char* option, int value, const ParameterSpec& spec) {
    if (!spec.Contains(value))
      throw UsageError(fmt::format("{} must be in [{}, {}] ({})", option, spec.min, spec.max, spec.unit));
  };
  check_range("--replay-sms", cli.replay_sms, kReplaySmsSpec);
  check_range("--replay-block-stride", cli.replay_block_stride, kReplayBlockStrideSpec);
  check_range("--priced-launches", cli.priced_launches, kPricedLaunchesPerBatchSpec);
  options.policy.hysteresis_nodes_per_query = cli.hysteresis;
  if (cli.threshold >= 0.0) {
    options.policy.threshold_nodes_per_query = cli.threshold;
    options.threshold_overridden = true;
  }
  options.switch_cost_cycles = cli.switch_cost;
  options.replay_sms = cli.replay_sms;
  options.replay_block_stride = cli.replay_block_stride;
  options.priced_launches = cli.priced_launches;
  return options;
}

BackendPreset BackendPresetOf(const SchedulerCli& cli) {
  return cli.backend_params.empty() ? DefaultPreset() : LoadBackendPreset(cli.backend_params);
}

BackendParameters BackendParametersOf(const SchedulerCli& cli) { return BackendPresetOf(cli).backend; }

namespace {

std::string Join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

void PrintLedgerSummary(std::ostream& out, const LedgerSummary& l, const LedgerOptions& options, double clock_hz,
                        const std::string& what, const std::string& counter) {
  auto emit = [&out](const char* format, const auto&... args) {
    out << fmt::format(fmt::runtime(format), args...) << '\n';
  };
  const std::string policy = ToString(options.policy);
  emit("modelled time (every {} priced on every backend; {} policy; {}):", what.c_str(), policy.c_str(),
       DescribeMemoryReplay(l.replay_sms, l.replay_block_stride).c_str());
  if (l.estimated_launches > 0)
    emit("  {} of {} launches priced as the mean of the recorded launches of their batch (--priced-launches {})",
         l.estimated_launches, l.launches, options.priced_launches);
  for (std::size_t b = 0; b < l.backends.size(); ++b)
    emit("  static {:<12} {:14.0f} cycles  {:9.4f} s{}", l.backends[b].c_str(), l.static_total_cycles[b],
         l.static_total_cycles[b] / clock_hz, l.backends[b] == l.best_static ? "  (best static)" : "");
  emit("  {:<19} {:14.0f} cycles  {:9.4f} s  ({} {}, {:.0f} cycles each)", policy.c_str(), l.policy_total_cycles,
       l.policy_total_cycles / clock_hz, l.switches, l.switches == 1 ? "switch" : "switches", l.switch_cost_cycles);
  const std::string over = l.oracle_candidates.size() == l.backends.size() ? std::string("all backends")
                                                                           : "{" + Join(l.oracle_candidates) + "}";
  emit("  oracle {:<12} {:14.0f} cycles  {:9.4f} s  (hindsight over {})", "", l.oracle_total_cycles,
       l.oracle_total_cycles / clock_hz, over.c_str());
  if (options.policy.kind == SchedulerKind::kThreshold)
    emit("  threshold {:.1f} {} ({})", l.threshold, counter.c_str(),
         options.threshold_overridden ? "given"
                                      : (l.threshold_has_crossing ? "crossover of the cost models" : "no crossover"));
  if (std::isnan(l.oracle_agreement_percent)) {
    emit("  gap to oracle {:.2f}%", l.gap_to_oracle_percent);
    return;
  }
  // "launch" -> "launches", "update" -> "updates".
  const std::string whats = what + (what.size() >= 2 && what.compare(what.size() - 2, 2, "ch") == 0 ? "es" : "s");
  emit(
      "  gap to oracle {:.2f}%; the oracle's choice in {:.1f}% of priced {} ({:.1f}% counting one within {:.0f}% of "
      "its cycles); followed {} of its {} lasting changes (>= {} {})",
      l.gap_to_oracle_percent, l.oracle_agreement_percent, whats.c_str(), l.oracle_equivalent_percent,
      LedgerSummary::kEquivalentPercent, l.oracle_lasting_changes_followed, l.oracle_lasting_changes,
      LedgerSummary::kLastingIterations, whats.c_str());
}

nlohmann::json LedgerSummaryJson(const LedgerSummary& l, const LedgerOptions& options) {
  nlohmann::json statics = nlohmann::json::object();
  for (std::size_t b = 0; b < l.backends.size(); ++b) statics[l.backends[b]] = l.static_total_cycles[b];
  auto number_or_null = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"policy", ToString(options.policy)},
          {"candidates", l.oracle_candidates},
          {"static_total_cycles", statics},
          {"policy_total_cycles", l.policy_total_cycles},
          {"oracle_total_cycles", l.oracle_total_cycles},
          {"oracle_candidates", l.oracle_candidates},
          {"best_static", l.best_static},
          {"switches", l.switches},
          {"switch_cost_cycles", l.switch_cost_cycles},
          {"threshold_nodes_per_query", number_or_null(l.threshold)},
          {"threshold_has_crossing", l.threshold_has_crossing},
          {"gap_to_oracle_percent", l.gap_to_oracle_percent},
          {"oracle_agreement_percent", number_or_null(l.oracle_agreement_percent)},
          {"oracle_equivalent_percent", number_or_null(l.oracle_equivalent_percent)},
          {"oracle_lasting_changes", l.oracle_lasting_changes},
          {"oracle_lasting_changes_followed", l.oracle_lasting_changes_followed},
          {"replay_sms", l.replay_sms},
          {"replay_block_stride", l.replay_block_stride},
          {"launches", l.launches},
          {"estimated_launches", l.estimated_launches}};
}

}  // namespace rc
