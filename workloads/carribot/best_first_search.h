#pragma once
// A* and weighted A* over any discrete state space, with flat per-state
// arrays that are allocated once and reset only where a query touched them.
//
// A Space provides (checked at compile time, no virtual calls per edge):
//   std::size_t state_count() const;
//   double Heuristic(StateId s) const;    // to the current goal, consistent
//   bool IsGoal(StateId s) const;
//   template <class IsClosed, class Visit>
//   void ExpandValid(StateId s, const IsClosed& closed, const Visit& visit);
//       calls visit(next, edge_cost, motion, heuristic(next)) for every
//       collision-free motion out of s whose target is not closed(next), in a
//       fixed order; the space may skip its collision checks for closed
//       targets, and computes the heuristic from coordinates it already has
//   StateId Predecessor(StateId s, std::uint8_t motion) const;
//       the state that `motion` into s came from
//
// Search: f = g + weight * h. Weight 1 with a consistent heuristic is A*
// (optimal); weight w > 1 is weighted A* (cost at most w times optimal).
// Closed states are never reopened: with a consistent h and w = 1 a closed
// state's g is already optimal; for w > 1 the w-suboptimality bound holds
// without reopening (Likhachev et al., ARA*, NIPS 2003). Ties: see
// indexed_min_heap.h. The goal test is made when a state is popped, so the
// returned path is optimal (w = 1), and the goal pop is not an expansion.
//
// Memory: 8 (g) + 1 (parent motion) bytes per state, plus the heap's 4-byte
// position per state and 24 bytes per queued state. The Intel map at scale 4
// with 8 headings (16.6 M states) peaks at 284 MB in all, RoWild 425 MB.
#include <cstdint>
#include <limits>
#include <vector>

#include "workloads/carribot/indexed_min_heap.h"

namespace rc {

enum class SearchOutcome { kReachedGoal, kExhausted, kExpansionLimit };

struct SearchCounters {
  std::uint64_t expanded = 0;   // states popped and expanded (the goal pop excluded)
  std::uint64_t generated = 0;  // pushes and decrease-keys (g improvements)
};

class BestFirstSearch {
 public:
  static constexpr std::uint8_t kStartMotion = 0xFF;  // parent marker of start states

  explicit BestFirstSearch(std::size_t state_count)
      : g_(state_count, kUnreached), parent_motion_(state_count, kStartMotion), heap_(state_count) {}

  std::size_t state_count() const { return g_.size(); }

  // Runs one query from every state in `starts` (g = 0 each; several starts
  // model "any start heading"). max_expansions = 0 means no limit. On
  // kReachedGoal, *goal holds the goal state reached.
  template <class Space>
  SearchOutcome Run(Space& space, const std::vector<StateId>& starts, double weight, std::uint64_t max_expansions,
                    StateId* goal, SearchCounters* counters) {
    Reset();
    *counters = {};
    for (const StateId s : starts) {
      if (g_[s] == 0.0) continue;  // listed twice
      Touch(s, 0.0, kStartMotion);
      heap_.PushOrDecrease(s, weight * space.Heuristic(s), 0.0);
    }
    const auto is_closed = [this](StateId s) { return heap_.IsClosed(s); };
    while (!heap_.empty()) {
      const StateId current = heap_.PopMin();
      if (space.IsGoal(current)) {
        *goal = current;
        return SearchOutcome::kReachedGoal;
      }
      if (max_expansions != 0 && counters->expanded >= max_expansions) return SearchOutcome::kExpansionLimit;
      ++counters->expanded;
      const double g_current = g_[current];
      space.ExpandValid(current, is_closed, [&](StateId next, double cost, std::uint8_t motion, double h_next) {
        const double g_next = g_current + cost;
        if (!(g_next < g_[next])) return;
        Touch(next, g_next, motion);
        heap_.PushOrDecrease(next, g_next + weight * h_next, g_next);
        ++counters->generated;
      });
    }
    return SearchOutcome::kExhausted;
  }

  // Cost of the best path found to s in the last query (infinity if none).
  double g(StateId s) const { return g_[s]; }

  // States from a start to `goal`, following parent motions back.
  template <class Space>
  std::vector<StateId> PathTo(const Space& space, StateId goal) const {
    std::vector<StateId> reversed{goal};
    StateId s = goal;
    while (parent_motion_[s] != kStartMotion) {
      s = space.Predecessor(s, parent_motion_[s]);
      reversed.push_back(s);
    }
    return {reversed.rbegin(), reversed.rend()};
  }

  std::uint8_t parent_motion(StateId s) const { return parent_motion_[s]; }

 private:
  static constexpr double kUnreached = std::numeric_limits<double>::infinity();

  void Touch(StateId s, double g, std::uint8_t motion) {
    if (g_[s] == kUnreached) touched_.push_back(s);
    g_[s] = g;
    parent_motion_[s] = motion;
  }
  void Reset() {
    for (const StateId s : touched_) {
      g_[s] = kUnreached;
      heap_.ForgetState(s);
    }
    touched_.clear();
    heap_.ClearQueue();
  }

  std::vector<double> g_;
  std::vector<std::uint8_t> parent_motion_;
  IndexedMinHeap heap_;
  std::vector<StateId> touched_;
};

}  // namespace rc
