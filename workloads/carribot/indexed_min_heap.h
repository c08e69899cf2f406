#pragma once
// A 4-ary min-heap of search states with decrease-key, for A*. Four children
// per node halve the depth of a binary heap, so a pop (the hot path of grid
// A*: about half its time on the MovingAI maps) moves fewer entries. On
// 64room_005, 2-, 4- and 8-ary heaps were within the noise of a shared
// machine of each other, 4-ary never the slowest.
//
// Order (the documented tie-breaking of every CarriBot search): smaller f
// first; among equal f, larger g first (the deeper state, which is nearer the
// goal and makes A* on open ground expand only the states of one path); then
// the smaller sequence number, i.e. the state pushed or improved earliest.
// The order is total, so a search is deterministic.
//
// Every state's heap position lives in a flat array sized to the state space
// (4 bytes per state), which also records whether a state was never pushed or
// already popped (closed). Reset() costs O(states touched), not O(all states),
// so one heap serves many queries.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rc {

using StateId = std::uint32_t;

class IndexedMinHeap {
 public:
  explicit IndexedMinHeap(std::size_t state_count);

  bool empty() const { return entries_.empty(); }
  std::size_t size() const { return entries_.size(); }
  bool IsClosed(StateId s) const { return position_[s] == kClosed; }
  bool Contains(StateId s) const { return position_[s] < kClosed; }

  // Inserts s, or replaces its key if it is queued (A* only lowers keys). The
  // state must not be closed (std::logic_error).
  void PushOrDecrease(StateId s, double f, double g);
  // Removes the minimum and marks it closed.
  StateId PopMin();
  // Forgets everything about s (never pushed). The caller resets every state
  // it pushed; entries still queued are dropped by ClearQueue().
  void ForgetState(StateId s) { position_[s] = kUnseen; }
  void ClearQueue() {
    entries_.clear();
    next_sequence_ = 0;
  }

 private:
  static constexpr std::uint32_t kUnseen = 0xFFFFFFFFu;
  static constexpr std::uint32_t kClosed = 0xFFFFFFFEu;

  static constexpr std::size_t kArity = 4;

  struct Entry {
    double f;
    double g;
    std::uint32_t sequence;  // per query; a query pushes far fewer than 2^32 times
    StateId state;
  };
  static bool Before(const Entry& a, const Entry& b) {
    if (a.f != b.f) return a.f < b.f;
    if (a.g != b.g) return a.g > b.g;
    return a.sequence < b.sequence;
  }
  void SiftUp(std::size_t i);
  void SiftDown(std::size_t i);
  void Place(std::size_t i, const Entry& e) {
    entries_[i] = e;
    position_[e.state] = static_cast<std::uint32_t>(i);
  }

  std::vector<Entry> entries_;
  std::vector<std::uint32_t> position_;
  std::uint32_t next_sequence_ = 0;
};

}  // namespace rc
