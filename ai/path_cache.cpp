#include "ai/path_cache.h"

#include <algorithm>

namespace zonesim::ai {

const GridPath* PathCache::find(Cell start, Cell goal, int* expanded) {
  auto it = index_.find(key(start, goal));
  if (it == index_.end()) {
    ++misses_;
    return nullptr;
  }
  ++hits_;
  lru_.splice(lru_.begin(), lru_, it->second);
  if (expanded) *expanded = it->second->expanded;
  return &it->second->path;
}

void PathCache::insert(Cell start, Cell goal, const GridPath& path, int expanded) {
  if (capacity_ == 0) return;
  std::uint64_t k = key(start, goal);
  auto it = index_.find(k);
  if (it != index_.end()) {
    it->second->path = path;
    it->second->expanded = expanded;
    lru_.splice(lru_.begin(), lru_, it->second);
    return;
  }
  if (lru_.size() >= capacity_) {
    index_.erase(lru_.back().key);
    lru_.pop_back();
  }
  lru_.push_front(Entry{k, path, expanded});
  index_[k] = lru_.begin();
}

void PathCache::cellClosed(Cell c) {
  for (auto it = lru_.begin(); it != lru_.end();) {
    if (std::find(it->path.cells.begin(), it->path.cells.end(), c) != it->path.cells.end()) {
      index_.erase(it->key);
      it = lru_.erase(it);
    } else {
      ++it;
    }
  }
}

void PathCache::clear() {
  lru_.clear();
  index_.clear();
}

}  // namespace zonesim::ai
