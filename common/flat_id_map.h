#pragma once
// A hash map from non-zero 64-bit ids to small values, stored flat: open addressing with linear
// probing over one array, so a lookup touches one or two cache lines and inserting allocates
// only when the table grows. Erasing shifts the following run back (no tombstones), so the
// table never degrades under churn. Used where std::unordered_map's node per entry dominated a
// hot loop (the gateway's per-player views). Id 0 marks an empty slot and cannot be a key.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

namespace zonesim {

template <typename V>
class FlatIdMap {
 public:
  /// The value for id, or nullptr.
  V* find(std::uint64_t id) { return const_cast<V*>(std::as_const(*this).find(id)); }
  const V* find(std::uint64_t id) const {
    if (size_ == 0) return nullptr;
    for (std::size_t i = home(id);; i = next(i)) {
      if (slots_[i].id == id) return &slots_[i].value;
      if (slots_[i].id == 0) return nullptr;
    }
  }
  bool contains(std::uint64_t id) const { return find(id) != nullptr; }

  /// Inserts (id, value) unless id is present; returns the held value and whether it was new.
  /// Throws std::invalid_argument for id 0.
  std::pair<V*, bool> tryEmplace(std::uint64_t id, const V& value) {
    if (id == 0) throw std::invalid_argument("FlatIdMap: id 0 is reserved for empty slots");
    if ((size_ + 1) * 2 > slots_.size()) grow();
    std::size_t i = home(id);
    for (; slots_[i].id != 0; i = next(i))
      if (slots_[i].id == id) return {&slots_[i].value, false};
    slots_[i] = {id, value};
    ++size_;
    return {&slots_[i].value, true};
  }
  /// Sets id's value, inserting it if absent.
  void insertOrAssign(std::uint64_t id, const V& value) {
    auto [held, inserted] = tryEmplace(id, value);
    if (!inserted) *held = value;
  }

  /// Removes id; false if absent.
  bool erase(std::uint64_t id) {
    if (size_ == 0) return false;
    std::size_t i = home(id);
    while (slots_[i].id != id) {
      if (slots_[i].id == 0) return false;
      i = next(i);
    }
    removeAt(i);
    return true;
  }

  /// Calls f(id, value&) for every entry and removes those for which it returns true.
  template <typename F>
  void eraseIf(F&& f) {
    // Removing shifts later entries of the run back into slot i: look at slot i again. An entry
    // that wraps past the end may land before i and be visited twice; f must be idempotent for
    // entries it keeps (all callers here only read or set fields to the same value).
    for (std::size_t i = 0; i < slots_.size();) {
      if (slots_[i].id != 0 && f(slots_[i].id, slots_[i].value))
        removeAt(i);
      else
        ++i;
    }
  }
  /// Calls f(id, value&) for every entry, in no particular order.
  template <typename F>
  void forEach(F&& f) {
    for (Slot& s : slots_)
      if (s.id != 0) f(s.id, s.value);
  }
  template <typename F>
  void forEach(F&& f) const {
    for (const Slot& s : slots_)
      if (s.id != 0) f(s.id, s.value);
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  void clear() {
    for (Slot& s : slots_) s.id = 0;
    size_ = 0;
  }

 private:
  struct Slot {
    std::uint64_t id = 0;
    V value{};
  };
  // Fibonacci hashing spreads sequential ids (the zones hand them out in runs).
  std::size_t home(std::uint64_t id) const {
    return std::size_t((id * 0x9E3779B97F4A7C15ULL) >> shift_);
  }
  std::size_t next(std::size_t i) const { return (i + 1) & (slots_.size() - 1); }
  void removeAt(std::size_t hole) {
    // Backward shift: move each later entry of the run into the hole when the hole lies
    // between its home and its slot (cyclically), so every entry stays reachable from home.
    std::size_t i = hole;
    for (;;) {
      slots_[hole].id = 0;
      for (i = next(i);; i = next(i)) {
        if (slots_[i].id == 0) {
          --size_;
          return;
        }
        std::size_t h = home(slots_[i].id);
        bool movable = hole <= i ? (h <= hole || h > i) : (h <= hole && h > i);
        if (movable) break;
      }
      slots_[hole] = slots_[i];
      hole = i;
    }
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    std::size_t capacity = old.empty() ? 16 : old.size() * 2;
    slots_.assign(capacity, Slot{});
    shift_ = 64;
    for (std::size_t c = capacity; c > 1; c >>= 1) --shift_;
    size_ = 0;
    for (const Slot& s : old)
      if (s.id != 0) tryEmplace(s.id, s.value);
  }

  std::vector<Slot> slots_;
  std::size_t size_ = 0;
  int shift_ = 64;
};

}  // namespace zonesim
