#pragma once
// Least-recently-used cache of grid paths keyed by (start, goal). A closed cell drops only the
// paths through it (the others stay valid and, since the map only lost options, optimal); an
// opened cell may shorten any path, so it clears the cache. Each path keeps the number of nodes
// its planning expanded, so a caller that charges a budget can charge a hit the same.

#include <cstdint>
#include <list>
#include <unordered_map>

#include "ai/grid_path.h"

namespace zonesim::ai {

/// Bounded LRU cache of paths; lookups never iterate the hash map, so eviction is deterministic.
class PathCache {
 public:
  /// A cache holding at most `capacity` paths (0 disables it).
  explicit PathCache(std::size_t capacity) : capacity_(capacity) {}

  /// The cached path from `start` to `goal`, or nullptr; a hit becomes most recently used and
  /// sets `*expanded` (when given) to the count stored with it.
  const GridPath* find(Cell start, Cell goal, int* expanded = nullptr);
  /// Stores a path and the nodes its planning expanded, evicting the least recently used one
  /// when full.
  void insert(Cell start, Cell goal, const GridPath& path, int expanded = 0);
  /// Drops every path through `c` (a door closed there).
  void cellClosed(Cell c);
  /// Drops everything (a cell opened: any path may now be shorter).
  void clear();
  /// Number of cached paths.
  std::size_t size() const { return lru_.size(); }
  /// Lookups that found a path.
  std::uint64_t hits() const { return hits_; }
  /// Lookups that did not.
  std::uint64_t misses() const { return misses_; }

 private:
  struct Entry {
    std::uint64_t key;
    GridPath path;
    int expanded = 0;
  };
  static std::uint64_t key(Cell s, Cell g) {
    return (std::uint64_t(std::uint16_t(s.x)) << 48) | (std::uint64_t(std::uint16_t(s.y)) << 32) |
           (std::uint64_t(std::uint16_t(g.x)) << 16) | std::uint64_t(std::uint16_t(g.y));
  }

  std::size_t capacity_;
  std::list<Entry> lru_;  // most recently used first
  std::unordered_map<std::uint64_t, std::list<Entry>::iterator> index_;
  std::uint64_t hits_ = 0;
  std::uint64_t misses_ = 0;
};

}  // namespace zonesim::ai
