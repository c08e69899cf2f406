#pragma once
// Per-iteration backend selection (the RoboGPU paper's DeliBot result:
// switching between RoboCore and the CUDA cores every iteration beats both).
//
// Policies, each deciding an iteration from what the previous iterations
// measured, never from the iteration it decides:
//   static:<backend>  always the same backend;
//   adaptive          (default) a cost predictor: each candidate's modelled
//                     cycles on the previous iteration's recorded work
//                     predict its cycles on the next. What decides the
//                     winner in these models (divergence, locality, ray
//                     length, launch) is in that prediction, which a
//                     threshold on one counter cannot see. A switch is made
//                     once the predicted savings of a rival, summed over
//                     consecutive iterations, pay for the switch ("rent or
//                     buy": regret against the current backend, reset by
//                     every switch), so a change lasting a few iterations
//                     is not chased;
//   threshold         the paper's policy: the previous iteration's average
//                     nodes per query (RoboCore's PUSH counter) against a
//                     threshold; long traversals go to high_backend, short
//                     ones to low_backend; hysteresis keeps a noisy counter
//                     from flapping;
//   oracle            hindsight: the cheapest sequence over the whole run,
//                     switch costs included (a shortest path over iterations
//                     x candidates). Used only for grading.
// The adaptive policy and the oracle choose among the same candidates
// (default: every modelled backend). A switch costs switch_cost_cycles,
// charged to the iteration that switches.
//
// The adaptive policy cannot beat static when the previous iteration does
// not predict the next (the workload changes faster than one iteration),
// and lags a lasting change by about switch_cost / (per-iteration saving)
// iterations.
#include <cstddef>
#include <string>
#include <vector>

namespace rc {

enum class SchedulerKind { kStatic, kAdaptive, kThreshold, kOracle };

struct SchedulerOptions {
  SchedulerKind kind = SchedulerKind::kAdaptive;
  std::string static_backend = "robocore";
  // adaptive and oracle: the backends they choose among (empty: every
  // modelled backend).
  std::vector<std::string> candidates;
  // adaptive: where it starts (empty: the first candidate).
  std::string initial_backend;
  // threshold: the two backends and the counter's threshold.
  std::string high_backend = "robocore";    // above the threshold
  std::string low_backend = "simt";         // at or below it
  double threshold_nodes_per_query = 0.0;   // the crossover
  double hysteresis_nodes_per_query = 0.0;  // margin around the threshold, >= 0
  double switch_cost_cycles = 0.0;          // charged on every change of backend
};

// Parses "static:<backend>", "adaptive", "threshold", "oracle", or a bare
// backend name (= static). Throws std::invalid_argument otherwise.
SchedulerOptions ParseSchedulerPolicy(const std::string& text, const std::vector<std::string>& backend_names);
// Parses a comma-separated candidate list, each a known backend, no
// repeats. Throws std::invalid_argument otherwise.
std::vector<std::string> ParseCandidates(const std::string& text, const std::vector<std::string>& backend_names);
std::string ToString(const SchedulerOptions& options);

// What an iteration measured, as the next decision sees it.
struct IterationObservation {
  bool ran = false;                      // false: no kernel work; the choice stays
  double nodes_per_query = -1.0;         // the traversal counter
  std::vector<double> candidate_cycles;  // modelled cycles on each candidate (adaptive)
};

// The online policies (static, adaptive, threshold): one decision per
// iteration from what the previous iteration measured.
class OnlineScheduler {
 public:
  // `candidates`: the adaptive policy's (the oracle's too), in order.
  OnlineScheduler(SchedulerOptions options, std::vector<std::string> candidates);
  // The backend for the next iteration, from the previous iteration.
  const std::string& Choose(const IterationObservation& previous);
  const std::string& current() const { return current_; }

 private:
  SchedulerOptions options_;
  std::vector<std::string> candidates_;
  std::vector<double> regret_;  // adaptive: per candidate, predicted savings not yet acted on
  std::string current_;
};

// cycles[i][b]: modelled cycles of iteration i on candidate b.
// Returns the candidate index per iteration minimizing the total cycles plus
// switch_cost_cycles per change (the first iteration's choice is free).
std::vector<std::size_t> OracleSchedule(const std::vector<std::vector<double>>& cycles, double switch_cost_cycles);

// Total cycles of a schedule, switch costs included.
double ScheduleCost(const std::vector<std::vector<double>>& cycles, const std::vector<std::size_t>& choice,
                    double switch_cost_cycles);

}  // namespace rc
