#pragma once
// Jump point search's open list: a binary min-heap of 16-byte entries with lazy deletion (an
// improved node is pushed again; its old entry, with a larger f, pops after it and is skipped
// as closed). Ties on f go to the entry nearer the goal (the deeper one, as in popsBefore of
// ai/open_order.h, whose exact g would make entries 24 bytes: here h is kept to 32 bits, which
// can only reorder entries whose h differ by less than 2^-16 cells, and saturates at 2^16
// cells, beyond which ties on f fall to the index: a landmark bound on a winding maze can
// exceed it), then to the lower index, so the order never depends on insertion order.

#include <algorithm>
#include <cstdint>
#include <vector>

namespace zonesim::ai {

/// Min-heap of (f, h, node) for JumpPointSearch; keeps its capacity across searches.
class JpsOpenList {
 public:
  /// One queued node.
  struct Entry {
    std::int64_t f;     ///< g + h, fixed point (ai/fixed_cost.h)
    std::uint32_t h;    ///< h in units of 2^24 fixed-point units, for ties on f
    std::int32_t node;  ///< the node's index
  };

  /// Empties the list (capacity kept).
  void clear() { heap_.clear(); }
  /// True when nothing is queued.
  bool empty() const { return heap_.empty(); }
  /// Queues node `node` with cost so far `g` and heuristic `h` (fixed point).
  void push(std::int32_t node, std::int64_t g, std::int64_t h) {
    Entry e{g + h, std::uint32_t(std::min<std::int64_t>(h >> 24, 0xFFFFFFFF)), node};
    std::size_t i = heap_.size();
    heap_.push_back(e);
    while (i > 0) {
      const std::size_t parent = (i - 1) / 2;
      if (!before(e, heap_[parent])) break;
      heap_[i] = heap_[parent];
      i = parent;
    }
    heap_[i] = e;
  }
  /// Removes and returns the entry that comes first.
  Entry pop() {
    const Entry top = heap_.front();
    const Entry last = heap_.back();
    heap_.pop_back();
    const std::size_t n = heap_.size();
    if (n == 0) return top;
    std::size_t i = 0;
    for (;;) {
      std::size_t child = 2 * i + 1;
      if (child >= n) break;
      if (child + 1 < n && before(heap_[child + 1], heap_[child])) ++child;
      if (!before(heap_[child], last)) break;
      heap_[i] = heap_[child];
      i = child;
    }
    heap_[i] = last;
    return top;
  }

 private:
  static bool before(const Entry& a, const Entry& b) {
    if (a.f != b.f) return a.f < b.f;
    if (a.h != b.h) return a.h < b.h;
    return a.node < b.node;
  }

  std::vector<Entry> heap_;
};

}  // namespace zonesim::ai
