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
  } else if (text == "oracle") {
    options.kind = SchedulerKind::kOracle;
  } else {
    const std::string prefix = "static:";
    const std::string name = text.rfind(prefix, 0) == 0 ? text.substr(prefix.size()) : text;
    if (!known(name)) {
      std::string list;
      for (const auto& n : backend_names) list += (list.empty() ? "" : ", ") + n;
      throw std::invalid_argument("unknown backend policy '" + text + "' (expected adaptive, oracle, or static:<" +
                                  list + ">)");
    }
    options.kind = SchedulerKind::kStatic;
    options.static_backend = name;
  }
  return options;
}

std::string ToString(const SchedulerOptions& options) {
  switch (options.kind) {
    case SchedulerKind::kStatic: return "static:" + options.static_backend;
    case SchedulerKind::kAdaptive: return "adaptive";
    case SchedulerKind::kOracle: return "oracle";
  }
  return "?";
}

OnlineScheduler::OnlineScheduler(SchedulerOptions options) : options_(std::move(options)) {
  if (options_.kind == SchedulerKind::kOracle)
    throw std::invalid_argument("the oracle is not an online policy; use OracleSchedule");
  if (!(options_.hysteresis_nodes_per_query >= 0.0))
    throw std::invalid_argument("hysteresis must be >= 0 nodes per query");
  // Before anything was measured the adaptive policy starts on the
  // traversal unit: the first iterations of a global localization cast the
  // longest rays (the paper's narrative). If the cost models have no
  // crossover because the CUDA cores win at every length (threshold +inf),
  // it starts, and stays, on them.
  if (options_.kind == SchedulerKind::kStatic)
    current_ = options_.static_backend;
  else
    current_ = std::isinf(options_.threshold_nodes_per_query) ? options_.low_backend : options_.high_backend;
}

const std::string& OnlineScheduler::Choose(double previous_nodes_per_query) {
  if (options_.kind != SchedulerKind::kAdaptive || previous_nodes_per_query < 0.0) return current_;
  const double t = options_.threshold_nodes_per_query, h = options_.hysteresis_nodes_per_query;
  if (current_ == options_.high_backend) {
    if (previous_nodes_per_query <= t - h) current_ = options_.low_backend;
  } else {
    if (previous_nodes_per_query > t + h) current_ = options_.high_backend;
  }
  return current_;
}

std::vector<std::size_t> OracleSchedule(const std::vector<std::vector<double>>& cycles, double switch_cost_cycles) {
  const std::size_t n = cycles.size();
  if (n == 0) return {};
  const std::size_t k = cycles.front().size();
  if (k == 0) throw std::invalid_argument("oracle needs at least one candidate backend");
  // best[b]: cheapest total for iterations [0, i] ending on b; from[i][b]
  // the predecessor. Ties keep the lower index, so the result is unique.
  std::vector<double> best(cycles[0]);
  std::vector<std::vector<std::size_t>> from(n, std::vector<std::size_t>(k, 0));
  for (std::size_t i = 1; i < n; ++i) {
    if (cycles[i].size() != k) throw std::invalid_argument("every iteration needs one cost per candidate");
    std::vector<double> next(k, std::numeric_limits<double>::infinity());
    for (std::size_t b = 0; b < k; ++b) {
      for (std::size_t a = 0; a < k; ++a) {
        const double total = best[a] + (a == b ? 0.0 : switch_cost_cycles) + cycles[i][b];
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
