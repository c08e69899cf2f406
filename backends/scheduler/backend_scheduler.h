#pragma once
// Per-iteration backend selection (the RoboGPU paper's DeliBot result:
// switching between RoboCore and the CUDA cores every iteration beats both).
//
// Policies:
//   static:<backend>  always the same backend;
//   adaptive          the previous iteration's average nodes per query
//                     (RoboCore's PUSH counter; on SIMT the kernel's own
//                     count) against a threshold: long traversals go to the
//                     traversal unit (high_backend), short ones to the CUDA
//                     cores (low_backend), which do not pay its launch and
//                     hand-off overhead. Hysteresis keeps a noisy counter
//                     from flapping: once on one side, the counter must cross
//                     the threshold by the hysteresis margin to switch back.
//   oracle            hindsight: the cheapest sequence of backends over the
//                     whole run, switch costs included (a shortest path over
//                     iterations x backends). Used only for grading.
// A switch costs switch_cost_cycles, charged to the iteration that switches.
//
// The adaptive policy cannot beat static when the counter does not predict
// the next iteration's cost (the workload changes faster than one
// iteration), or when one backend is cheaper at every counter value (no
// crossover: the threshold falls outside the observed range).
#include <cstddef>
#include <string>
#include <vector>

namespace rc {

enum class SchedulerKind { kStatic, kAdaptive, kOracle };

struct SchedulerOptions {
  SchedulerKind kind = SchedulerKind::kStatic;
  std::string static_backend = "robocore";
  std::string high_backend = "robocore";  // adaptive: above the threshold
  std::string low_backend = "simt";       // adaptive: at or below the threshold
  double threshold_nodes_per_query = 0.0; // adaptive: the crossover
  double hysteresis_nodes_per_query = 0.0;// adaptive: margin around the threshold, >= 0
  double switch_cost_cycles = 0.0;        // charged on every change of backend
};

// Parses "static:<backend>", "adaptive", "oracle", or a bare backend name
// (= static). Throws std::invalid_argument otherwise.
SchedulerOptions ParseSchedulerPolicy(const std::string& text, const std::vector<std::string>& backend_names);
std::string ToString(const SchedulerOptions& options);

// The online policies (static, adaptive): one decision per iteration from
// what the previous iteration measured.
class OnlineScheduler {
 public:
  explicit OnlineScheduler(SchedulerOptions options);
  // The backend for the next iteration. `previous_nodes_per_query` < 0 means
  // the previous iteration ran no query (or there was none): the choice stays.
  const std::string& Choose(double previous_nodes_per_query);
  const std::string& current() const { return current_; }

 private:
  SchedulerOptions options_;
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
