#include "workloads/carribot/indexed_min_heap.h"

#include <algorithm>
#include <stdexcept>

namespace rc {

IndexedMinHeap::IndexedMinHeap(std::size_t state_count) : position_(state_count, kUnseen) {
  if (state_count >= kClosed)
    throw std::invalid_argument("IndexedMinHeap: more states than 32-bit positions can address");
}

void IndexedMinHeap::PushOrDecrease(StateId s, double f, double g) {
  const std::uint32_t at = position_[s];
  if (at == kClosed) throw std::logic_error("IndexedMinHeap: push of a closed state");
  const Entry e{f, g, next_sequence_++, s};
  if (at == kUnseen) {
    entries_.push_back(e);
    Place(entries_.size() - 1, e);
    SiftUp(entries_.size() - 1);
    return;
  }
  // g only ever improves, but f = g + w*h can round to the old value while g
  // became smaller, which the order then ranks later: sift both ways.
  Place(at, e);
  SiftUp(at);
  SiftDown(position_[s]);
}

StateId IndexedMinHeap::PopMin() {
  const StateId top = entries_.front().state;
  const Entry last = entries_.back();
  entries_.pop_back();
  if (!entries_.empty()) {
    Place(0, last);
    SiftDown(0);
  }
  position_[top] = kClosed;
  return top;
}

void IndexedMinHeap::SiftUp(std::size_t i) {
  const Entry e = entries_[i];
  while (i > 0) {
    const std::size_t parent = (i - 1) / kArity;
    if (!Before(e, entries_[parent])) break;
    Place(i, entries_[parent]);
    i = parent;
  }
  Place(i, e);
}

void IndexedMinHeap::SiftDown(std::size_t i) {
  const Entry e = entries_[i];
  const std::size_t n = entries_.size();
  while (true) {
    const std::size_t first = kArity * i + 1;
    if (first >= n) break;
    std::size_t child = first;
    const std::size_t last = std::min(first + kArity, n);
    for (std::size_t c = first + 1; c < last; ++c)
      if (Before(entries_[c], entries_[child])) child = c;
    if (!Before(entries_[child], e)) break;
    Place(i, entries_[child]);
    i = child;
  }
  Place(i, e);
}

}  // namespace rc
