// The indexed heap against a brute-force reference: random pushes,
// decrease-keys and pops must come out in exactly the documented order.
#include "workloads/carribot/indexed_min_heap.h"

#include <gtest/gtest.h>

#include <random>
#include <tuple>
#include <vector>

namespace rc {
namespace {

struct Reference {
  double f, g;
  std::uint64_t sequence;
  bool queued = false;
  bool closed = false;
};

TEST(IndexedMinHeap, PopsInOrderOfFThenLargerGThenFirstPushed) {
  constexpr std::size_t kStates = 300;
  std::mt19937 rng(17);
  // Few distinct keys, so that ties on f and on (f, g) are frequent.
  std::uniform_int_distribution<int> key(0, 6), state(0, kStates - 1), action(0, 2);
  for (int round = 0; round < 20; ++round) {
    IndexedMinHeap heap(kStates);
    std::vector<Reference> ref(kStates);
    std::uint64_t sequence = 0;
    for (int step = 0; step < 3000; ++step) {
      if (action(rng) < 2) {
        const StateId s = static_cast<StateId>(state(rng));
        if (ref[s].closed) {
          EXPECT_THROW(heap.PushOrDecrease(s, 0, 0), std::logic_error);
          continue;
        }
        const double f = key(rng), g = key(rng);
        heap.PushOrDecrease(s, f, g);
        ref[s] = {f, g, sequence++, true, false};
      } else if (!heap.empty()) {
        StateId best = 0;
        bool any = false;
        for (StateId s = 0; s < kStates; ++s) {
          if (!ref[s].queued) continue;
          const auto key_of = [&](StateId t) { return std::make_tuple(ref[t].f, -ref[t].g, ref[t].sequence); };
          if (!any || key_of(s) < key_of(best)) best = s;
          any = true;
        }
        ASSERT_TRUE(any);
        ASSERT_EQ(heap.PopMin(), best) << "round " << round << " step " << step;
        ref[best].queued = false;
        ref[best].closed = true;
        EXPECT_TRUE(heap.IsClosed(best));
      }
      std::size_t queued = 0;
      for (const Reference& r : ref) queued += r.queued;
      ASSERT_EQ(heap.size(), queued);
    }
  }
}

TEST(IndexedMinHeap, ForgetStateMakesAStateNewAgain) {
  IndexedMinHeap heap(4);
  heap.PushOrDecrease(2, 1.0, 0.0);
  EXPECT_EQ(heap.PopMin(), 2u);
  EXPECT_TRUE(heap.IsClosed(2));
  heap.ForgetState(2);
  heap.ClearQueue();
  EXPECT_FALSE(heap.IsClosed(2));
  EXPECT_FALSE(heap.Contains(2));
  heap.PushOrDecrease(2, 5.0, 0.0);
  EXPECT_TRUE(heap.Contains(2));
}

}  // namespace
}  // namespace rc
