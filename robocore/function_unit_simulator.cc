#include "robocore/function_unit_simulator.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <tuple>

namespace rc {
namespace {

struct Waiting {
  int thread;
  int step;
  std::uint64_t ready;
  bool chained;
};

struct InFlight {
  int thread;
  int step;
  std::uint64_t done;
};

class Simulation {
 public:
  Simulation(const SectionTiming& section, const std::vector<SimulatedThread>& threads)
      : config_(section.config()), threads_(threads) {
    for (const SimulatedThread& t : threads) {
      auto it = plans_by_exit_.find(t.exit);
      if (it == plans_by_exit_.end()) it = plans_by_exit_.emplace(t.exit, section.Plan(t.exit)).first;
      plans_.push_back(&it->second);  // map nodes never move
    }
    result_.threads.resize(threads.size());
  }

  FunctionUnitSimulation Run(int threads_per_cycle) {
    if (threads_per_cycle < 1) throw std::invalid_argument("threads_per_cycle must be >= 1");
    const std::size_t n = threads_.size();
    // Far beyond any schedule these units can produce: a guard against a bug
    // that would loop forever.
    const std::uint64_t limit = 1'000'000'000ULL;
    while (finished_ < n) {
      Complete();
      for (int k = 0; k < threads_per_cycle && next_thread_ < n; ++k)
        Advance(static_cast<int>(next_thread_++), -1, now_);
      Accept();
      if (finished_ == n) break;
      if (++now_ > limit) throw std::logic_error("function-unit simulation did not finish");
    }
    return std::move(result_);
  }

 private:
  const std::vector<PlannedOp>& plan(int t) const { return *plans_[t]; }

  void Finish(int t, std::uint64_t at) {
    result_.threads[t].finish_cycle = at;
    result_.cycles = std::max(result_.cycles, at);
    ++finished_;
  }

  // Thread t has completed plan step `step` at cycle `at` (-1: it enters);
  // route it to its next unit, or finish it.
  void Advance(int t, int step, std::uint64_t at) {
    const std::vector<PlannedOp>& p = plan(t);
    for (int s = step + 1; s < static_cast<int>(p.size()); ++s) {
      const PlannedOp& op = p[s];
      if (op.ctrl) {  // CTRL checks the axis result as it leaves the SACT unit
        at += op.latency;
        if (op.fires) {
          result_.threads[t].exited_early = true;
          return Finish(t, at);
        }
        continue;
      }
      if (op.load) {
        at += threads_[t].load_latency_cycles;
        continue;
      }
      if (op.hop_before) ++result_.hops;
      const std::uint64_t ready = at + (op.hop_before ? config_.interconnect_hop_cycles : 0);
      waiting_[static_cast<int>(op.unit)].push_back({t, s, ready, op.chained});
      return;
    }
    Finish(t, at);
  }

  void Complete() {
    std::vector<InFlight> done;
    auto keep = std::partition(in_flight_.begin(), in_flight_.end(), [&](const InFlight& f) { return f.done > now_; });
    done.assign(keep, in_flight_.end());
    in_flight_.erase(keep, in_flight_.end());
    std::sort(done.begin(), done.end(), [](const InFlight& a, const InFlight& b) {
      return a.done != b.done ? a.done < b.done : a.thread < b.thread;
    });
    for (const InFlight& f : done) {
      const PlannedOp& op = plan(f.thread)[f.step];
      if (op.opcode == Opcode::kBox || op.opcode == Opcode::kEdge) ++result_.threads[f.thread].axes_tested;
      if (op.fires) result_.threads[f.thread].exited_early = true;
      Advance(f.thread, f.step, f.done);
    }
  }

  void Accept() {
    for (int u = 0; u < kOpUnitCount; ++u) {
      if (next_accept_[u] > now_) continue;
      std::vector<Waiting>& queue = waiting_[u];
      int best = -1;
      bool other_ready = false;
      for (int i = 0; i < static_cast<int>(queue.size()); ++i) {
        const Waiting& w = queue[i];
        if (w.ready > now_) continue;
        if (!w.chained) other_ready = true;
        if (best < 0) {
          best = i;
          continue;
        }
        const Waiting& b = queue[best];
        // The arbiter: chained first, then earliest arrival, then lowest thread.
        const auto key = [](const Waiting& x) { return std::make_tuple(!x.chained, x.ready, x.thread); };
        if (key(w) < key(b)) best = i;
      }
      if (best < 0) continue;
      const Waiting w = queue[best];
      queue.erase(queue.begin() + best);
      if (w.chained && other_ready) ++result_.chain_priority_wins;
      const PlannedOp& op = plan(w.thread)[w.step];
      in_flight_.push_back({w.thread, w.step, now_ + static_cast<std::uint64_t>(op.latency)});
      next_accept_[u] = now_ + static_cast<std::uint64_t>(op.initiation);
      result_.busy_cycles[u] += static_cast<std::uint64_t>(op.initiation);
    }
  }

  const DatapathConfig& config_;
  const std::vector<SimulatedThread>& threads_;
  std::vector<const std::vector<PlannedOp>*> plans_;
  std::map<std::uint8_t, std::vector<PlannedOp>> plans_by_exit_;
  std::array<std::vector<Waiting>, kOpUnitCount> waiting_;
  std::array<std::uint64_t, kOpUnitCount> next_accept_{};
  std::vector<InFlight> in_flight_;
  std::size_t next_thread_ = 0;
  std::size_t finished_ = 0;
  std::uint64_t now_ = 0;
  FunctionUnitSimulation result_;
};

}  // namespace

FunctionUnitSimulation SimulateFunctionUnit(const SectionTiming& section, const std::vector<SimulatedThread>& threads,
                                            int threads_accepted_per_cycle) {
  return Simulation(section, threads).Run(threads_accepted_per_cycle);
}

}  // namespace rc
