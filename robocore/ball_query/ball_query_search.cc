#include "robocore/ball_query/ball_query_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "robocore/section_timing.h"  // kNoExit

namespace rc {
namespace {

// Keeps a node only when rounding could not have pushed it past the radius.
constexpr double kMargin = 1e-12;  // relative

bool Before(const BallNeighbor& a, const BallNeighbor& b) {
  return a.distance < b.distance || (a.distance == b.distance && a.sequence < b.sequence);
}

// Squared Euclidean distance from q to the box [lo, hi].
double BoxDistanceSquared(const double* q, const double* lo, const double* hi, std::size_t n) {
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = q[i] < lo[i] ? lo[i] - q[i] : (q[i] > hi[i] ? q[i] - hi[i] : 0.0);
    sum += d * d;
  }
  return sum;
}

// The query point lies in [lo - rho, hi + rho] on every axis.
bool InGrownBox(const double* q, const double* lo, const double* hi, std::size_t n, double rho) {
  const double grow = rho * (1 + kMargin);
  for (std::size_t i = 0; i < n; ++i)
    if (lo[i] - q[i] > grow || q[i] - hi[i] > grow) return false;
  return true;
}

class Pass {
 public:
  Pass(const BallQueryTree& tree, const BallQueryConfig& config, const double* query, std::size_t k, bool shrink,
       BallQueryVisits* visits)
      : tree_(tree),
        sphere_(config.formulation == BallQueryFormulation::kPSphere),
        q_(query),
        n_(tree.dimension()),
        k_(k),
        shrink_(shrink),
        visits_(visits) {}

  // Fills best (sorted) with the states within rho (at most k).
  void Run(double rho, std::vector<BallNeighbor>& best) {
    rho_ = rho;
    best_ = &best;
    best.clear();
    stack_.clear();
    if (visits_) ++visits_->passes;
    const int root = tree_.root();
    if (root < 0) return;
    if (tree_.IsLeaf(root)) {  // one fetch of the root's slot: the state as child a
      Record(root, Offer(tree_.StateOf(root)) ? kNoExit : kBallQueryNoChild);
      return;
    }
    stack_.push_back({root, 0.0});
    while (!stack_.empty()) {
      const Entry e = stack_.back();
      stack_.pop_back();
      if (sphere_ && e.distance_squared > Radius2()) continue;  // dropped without a fetch
      Visit(e.node);
    }
    if (unbounded()) std::sort(best.begin(), best.end(), Before);
  }

 private:
  struct Entry {
    int node;
    double distance_squared;  // P-Sphere: to the node's box; P-Ray: 0
  };

  bool unbounded() const { return k_ == std::numeric_limits<std::size_t>::max(); }
  double Radius2() const { return rho_ * rho_ * (1 + kMargin); }

  void Record(int node, std::uint8_t exit) {
    if (!visits_) return;
    visits_->nodes.push_back(static_cast<std::uint32_t>(node));
    visits_->exits.push_back(exit);
  }

  // Tests a state child; true if it lies within rho (then it was offered).
  bool Offer(BallStateId id) {
    const double d = EuclideanDistance(tree_.Coordinates(id), q_, n_);
    if (!(d <= rho_)) return false;
    const BallNeighbor candidate{d, tree_.Sequence(id), id};
    std::vector<BallNeighbor>& best = *best_;
    if (unbounded()) {
      best.push_back(candidate);  // a radius query: sorted once at the end
    } else if (best.size() < k_) {
      best.insert(std::upper_bound(best.begin(), best.end(), candidate, Before), candidate);
    } else if (Before(candidate, best.back())) {
      best.pop_back();
      best.insert(std::upper_bound(best.begin(), best.end(), candidate, Before), candidate);
    }
    return true;
  }

  void Visit(int node) {
    bool any = false, state = false;
    Entry push[2];
    int pushes = 0;
    // Both children are tested against the radius the node started with;
    // the best list is updated after both tests, as in the programs.
    BallStateId states[2];
    int state_count = 0;
    for (int c = 0; c < 2; ++c) {
      const int child = tree_.Child(node, c);
      if (tree_.IsLeaf(child)) {
        const double d = EuclideanDistance(tree_.Coordinates(tree_.StateOf(child)), q_, n_);
        if (d <= rho_) {
          any = state = true;
          states[state_count++] = tree_.StateOf(child);
        }
      } else if (sphere_) {
        const double d2 = BoxDistanceSquared(q_, tree_.Lo(child), tree_.Hi(child), n_);
        if (d2 <= Radius2()) {
          any = true;
          push[pushes++] = {child, d2};
        }
      } else if (InGrownBox(q_, tree_.Lo(child), tree_.Hi(child), n_, rho_)) {
        any = true;
        push[pushes++] = {child, 0.0};
      }
    }
    // The stack pops from the back: push the entry to visit second first.
    // P-Sphere visits the nearer child first (ties: child a); P-Ray keeps
    // the stored order.
    if (pushes == 2) {
      const bool b_first = sphere_ && push[1].distance_squared < push[0].distance_squared;
      stack_.push_back(b_first ? push[0] : push[1]);
      stack_.push_back(b_first ? push[1] : push[0]);
    } else if (pushes == 1) {
      stack_.push_back(push[0]);
    }
    Record(node, !any ? kBallQueryNoChild : (!state ? kBallQueryNoState : kNoExit));
    for (int s = 0; s < state_count; ++s) Offer(states[s]);
    if (shrink_ && best_->size() == k_) rho_ = std::min(rho_, best_->back().distance);
  }

  const BallQueryTree& tree_;
  const bool sphere_;
  const double* q_;
  const std::size_t n_;
  const std::size_t k_;
  const bool shrink_;
  BallQueryVisits* visits_;
  double rho_ = 0;
  std::vector<BallNeighbor>* best_ = nullptr;
  std::vector<Entry> stack_;
};

}  // namespace

void BallNearestK(const BallQueryTree& tree, const BallQueryConfig& config, const double* query, std::size_t k,
                  std::vector<BallNeighbor>& out, BallQueryVisits* visits) {
  out.clear();
  if (visits) visits->clear();
  if (k == 0 || tree.empty()) return;
  const std::size_t want = std::min(k, tree.size());
  Pass pass(tree, config, query, k, config.early_exit, visits);
  double rho = config.sphere_radius;
  while (true) {
    pass.Run(rho, out);
    if (out.size() >= want) return;
    rho *= config.radius_growth;  // reaches +inf at worst, which holds every state
  }
}

void BallWithinRadius(const BallQueryTree& tree, const BallQueryConfig& config, const double* query, double radius,
                      std::vector<BallNeighbor>& out, BallQueryVisits* visits) {
  out.clear();
  if (visits) visits->clear();
  if (!(radius >= 0) || tree.empty()) return;
  Pass pass(tree, config, query, std::numeric_limits<std::size_t>::max(), false, visits);
  pass.Run(radius, out);
}

}  // namespace rc
