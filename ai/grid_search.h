#pragma once
// A* and Dijkstra on an 8-connected grid, with node records that live as long as the searcher:
// each record carries the generation of the search that last touched it, so a new search
// starts by bumping one counter instead of clearing the map, and once the heap has grown to
// its peak a query allocates nothing. The open list is an indexed binary heap with decrease-key:
// lazy deletion let stale entries pile up (five pushes per expansion on 8room_000) and popping
// them dominated the run time.

#include <cstdint>
#include <utility>
#include <vector>

#include "ai/grid_map.h"
#include "ai/grid_path.h"
#include "ai/landmark_heuristic.h"

namespace zonesim::ai {

/// Work done by the last search.
struct SearchStats {
  int expanded = 0;   ///< nodes taken off the open list and expanded
  int generated = 0;  ///< heap pushes
};

/// Reusable optimal grid searcher bound to one map (which may change between searches).
class GridSearch {
 public:
  /// Sizes the node records for `map`; the map must outlive the searcher.
  explicit GridSearch(const GridMap& map);

  /// Optimal 8-connected path without corner cutting; false (and `out` empty) when none.
  bool findPath(Cell start, Cell goal, GridPath& out);
  /// Estimates costs with `landmarks` as well as the octile distance while they are valid for
  /// the map (null: octile alone); they must outlive the searcher. Paths stay optimal.
  void useLandmarks(const LandmarkHeuristic* landmarks) { landmarks_ = landmarks; }
  /// As findPath, never leaving `bounds` (both ends must be inside).
  bool findPath(Cell start, Cell goal, const CellRect& bounds, GridPath& out);
  /// Dijkstra from `start` over `bounds`; distanceTo() then answers for any cell.
  void explore(Cell start, const CellRect& bounds);
  /// Cost from the last explore()'s start, or a negative value when unreached.
  double distanceTo(Cell c) const;
  /// The same cost in fixed point (ai/fixed_cost.h, exact sums of steps), or -1 when unreached.
  std::int64_t costTo(Cell c) const;
  /// Cells from the last explore()'s start to `c` (empty when unreached).
  void pathTo(Cell c, GridPath& out) const;
  /// Counters of the last search.
  const SearchStats& lastStats() const { return stats_; }
  /// The map searched.
  const GridMap& map() const { return map_; }
  /// Capacity of the node records and of the open list: once the open list reached its peak,
  /// a query leaves both unchanged (it allocates nothing).
  std::pair<std::size_t, std::size_t> storageCapacity() const {
    return {nodes_.capacity(), heap_.capacity()};
  }

 private:
  struct Node {
    std::int64_t g;  // fixed point, see HeapEntry
    std::int32_t parent;
    // stamp == generation_: open, stamp == generation_ + 1: closed, anything else: untouched.
    std::uint32_t stamp;
    std::int32_t heap_pos;  // position in heap_ while open
  };
  // Costs are integers in 2^-40 units (a cardinal step is 2^40, a diagonal sqrt(2) * 2^40
  // rounded). Doubles reached through different orders of 1 and sqrt(2) steps differ in their
  // last bits, and those bits broke f ties arbitrarily (defeating the prefer-deeper-g
  // tie-break); integer sums tie exactly, compare fast, and the octile heuristic in the same
  // units stays consistent. Distinct costs on maps this size differ by far more than the
  // rounding, so the order is that of the exact costs; lengths are reported from the cells.
  struct HeapEntry {
    std::int64_t f;
    std::int64_t g;
    std::int32_t idx;
  };

  // The shared loop: `goal` < 0 means explore everything reachable inside `bounds`.
  bool run(int start, int goal, const CellRect& bounds);
  void beginSearch();
  void heapPush(const HeapEntry& e);
  void heapDecrease(const HeapEntry& e);
  void siftUp(std::size_t i, const HeapEntry& e);
  HeapEntry heapPop();
  void tracePath(int goal, GridPath& out) const;

  const GridMap& map_;
  const LandmarkHeuristic* landmarks_ = nullptr;
  LandmarkHeuristic::Goal goal_landmarks_;  // kept to avoid allocating per query
  std::vector<Node> nodes_;
  std::vector<HeapEntry> heap_;
  std::uint32_t generation_ = 0;
  SearchStats stats_;
};

}  // namespace zonesim::ai
