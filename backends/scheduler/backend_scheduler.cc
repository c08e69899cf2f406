#include "backends/scheduler/backend_scheduler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rc {

SchedulerOptions ParseSchedulerPolicy(const std::string& text, const std::vector<std::string>& backend_names) {
  auto known = [&](const std::string& name) {
    return std::find(backend_names.begin(), backend_names.end(), name) != backend_names.end();
  };
  SchedulerOptions options;
  if (text == "adaptive") {
    options.kind = SchedulerKind::kAdaptive;
  } else if (text == "threshold") {
    options.kind = SchedulerKind::kThreshold;
  } else if (text == "oracle") {
    options.kind = SchedulerKind::kOracle;
  } else {
    const std::string prefix = "static:";
    const std::string name = text.rfind(prefix, 0) == 0 ? text.substr(prefix.size()) : text;
    if (!known(name)) {
      std::string list;
      for (const auto& n : backend_names) list += (list.empty() ? "" : "|") + n;
      throw std::invalid_argument("unknown backend policy '" + text +
                                  "' (expected adaptive, threshold, oracle, or static:<" + list + ">)");
    }
    options.kind = SchedulerKind::kStatic;
    options.static_backend = name;
  }
  return options;
}

std::vector<std::string> ParseCandidates(const std::string& text, const std::vector<std::string>& backend_names) {
  std::vector<std::string> out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = text.find(',', begin);
    const std::string name = text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    if (std::find(backend_names.begin(), backend_names.end(), name) == backend_names.end())
      throw std::invalid_argument("unknown candidate backend '" + name + "'");
    if (std::find(out.begin(), out.end(), name) != out.end())
      throw std::invalid_argument("candidate backend '" + name + "' named twice");
    out.push_back(name);
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return out;
}

std::string ToString(const SchedulerOptions& options) {
  switch (options.kind) {
    case SchedulerKind::kStatic: return "static:" + options.static_backend;
    case SchedulerKind::kAdaptive: return "adaptive";
    case SchedulerKind::kThreshold: return "threshold";
    case SchedulerKind::kOracle: return "oracle";
  }
  return "?";
}

OnlineScheduler::OnlineScheduler(SchedulerOptions options, std::vector<std::string> candidates)
    : options_(std::move(options)), candidates_(std::move(candidates)) {
  if (options_.kind == SchedulerKind::kOracle)
    throw std::invalid_argument("the oracle is not an online policy; use OracleSchedule");
  if (!(options_.hysteresis_nodes_per_query >= 0.0))
    throw std::invalid_argument("hysteresis must be >= 0 nodes per query");
  if (!(options_.switch_cost_cycles >= 0.0)) throw std::invalid_argument("switch cost must be >= 0 cycles");
  switch (options_.kind) {
    case SchedulerKind::kStatic: current_ = options_.static_backend; break;
    case SchedulerKind::kAdaptive:
      if (candidates_.empty()) throw std::invalid_argument("the adaptive policy needs at least one candidate");
      current_ = options_.initial_backend.empty() ? candidates_.front() : options_.initial_backend;
      if (std::find(candidates_.begin(), candidates_.end(), current_) == candidates_.end())
        throw std::invalid_argument("the adaptive policy starts on '" + current_ + "', which is not a candidate");
      regret_.assign(candidates_.size(), 0.0);
      break;
    default:
      // Before anything was measured the threshold policy starts on the
      // traversal unit: the first iterations of a global localization cast
      // the longest rays (the paper's narrative). If the cost models have
      // no crossover because the CUDA cores win at every length (threshold
      // +inf), it starts, and stays, on them.
      current_ = std::isinf(options_.threshold_nodes_per_query) ? options_.low_backend : options_.high_backend;
  }
}

const std::string& OnlineScheduler::Choose(const IterationObservation& previous) {
  if (!previous.ran) return current_;
  if (options_.kind == SchedulerKind::kThreshold) {
    const double n = previous.nodes_per_query;
    const double t = options_.threshold_nodes_per_query, h = options_.hysteresis_nodes_per_query;
    if (current_ == options_.high_backend) {
      if (n <= t - h) current_ = options_.low_backend;
    } else {
      if (n > t + h) current_ = options_.high_backend;
    }
  } else if (options_.kind == SchedulerKind::kAdaptive) {
    if (previous.candidate_cycles.size() != candidates_.size())
      throw std::invalid_argument("the adaptive policy needs one predicted cost per candidate");
    const std::size_t now =
        static_cast<std::size_t>(std::find(candidates_.begin(), candidates_.end(), current_) - candidates_.begin());
    // Regret: what each rival would have saved over the current backend in
    // the iterations since the last switch, never below zero (a rival is
    // not held back by the iterations it lost). The rival with the most
    // regret is taken once that pays for the switch; ties keep the earlier
    // candidate, so the choice is unique.
    std::size_t best = now;
    for (std::size_t b = 0; b < candidates_.size(); ++b) {
      if (b == now) continue;
      regret_[b] = std::max(0.0, regret_[b] + previous.candidate_cycles[now] - previous.candidate_cycles[b]);
      if (regret_[b] > 0.0 && regret_[b] >= options_.switch_cost_cycles && (best == now || regret_[b] > regret_[best]))
        best = b;
    }
    if (best != now) {
      current_ = candidates_[best];
      std::fill(regret_.begin(), regret_.end(), 0.0);
    }
  }
  return current_;
}

std::vector<std::size_t> OracleSchedule(const std::vector<std::vector<double>>& cycles, double switch_cost_cycles) {
  const std::size_t n = cycles.size();
  if (n == 0) return {};
  const std::size_t k = cycles.front().size();
  if (k == 0) throw std::invalid_argument("oracle needs at least one candidate backend");
  // best[b]: cheapest total for iterations [0, i] ending on b; from[i][b]
  // the predecessor. Ties stay on the same backend (an iteration with no
  // kernel work costs 0 everywhere and must not read as a switch), then keep
  // the lower index, so the result is unique.
  std::vector<double> best(cycles[0]);
  std::vector<std::vector<std::size_t>> from(n, std::vector<std::size_t>(k, 0));
  for (std::size_t i = 1; i < n; ++i) {
    if (cycles[i].size() != k) throw std::invalid_argument("every iteration needs one cost per candidate");
    std::vector<double> next(k);
    for (std::size_t b = 0; b < k; ++b) {
      next[b] = best[b] + cycles[i][b];
      from[i][b] = b;
      for (std::size_t a = 0; a < k; ++a) {
        if (a == b) continue;
        const double total = best[a] + switch_cost_cycles + cycles[i][b];
        if (total < next[b]) {
          next[b] = total;
          from[i][b] = a;
        }
      }
    }
    best.swap(next);
  }
  std::vector<std::size_t> choice(n);
  choice[n - 1] = static_cast<std::size_t>(std::min_element(best.begin(), best.end()) - best.begin());
  for (std::size_t i = n - 1; i > 0; --i) choice[i - 1] = from[i][choice[i]];
  return choice;
}

double ScheduleCost(const std::vector<std::vector<double>>& cycles, const std::vector<std::size_t>& choice,
                    double switch_cost_cycles) {
  double total = 0.0;
  for (std::size_t i = 0; i < choice.size(); ++i) {
    total += cycles[i][choice[i]];
    if (i > 0 && choice[i] != choice[i - 1]) total += switch_cost_cycles;
  }
  return total;
}

}  // namespace rc
