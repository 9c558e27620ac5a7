#pragma once
// Slots that are reused, addressed by handles carrying a generation: a handle to a slot that
// was freed and handed out again no longer resolves, so stale references are caught.

#include <cstdint>
#include <optional>
#include <vector>

namespace zonesim {

/// Index of a slot plus the generation it was issued in.
struct SlotHandle {
  std::uint32_t index = 0;
  std::uint32_t generation = 0;
  friend bool operator==(SlotHandle, SlotHandle) = default;
  /// Packs into 64 bits (e.g. to send over the wire).
  std::uint64_t packed() const { return (std::uint64_t{generation} << 32) | index; }
  static SlotHandle unpack(std::uint64_t v) { return {std::uint32_t(v), std::uint32_t(v >> 32)}; }
};

/// A pool of T in reusable slots; lookups check the generation.
template <typename T>
class GenerationalPool {
 public:
  SlotHandle insert(T value) {
    std::uint32_t index;
    if (!free_.empty()) {
      index = free_.back();
      free_.pop_back();
    } else {
      index = std::uint32_t(slots_.size());
      slots_.push_back({});
    }
    Slot& s = slots_[index];
    s.value = std::move(value);
    s.live = true;
    ++live_count_;
    return {index, s.generation};
  }

  /// The value if the handle is current; nullptr if the slot was freed or reused since.
  T* get(SlotHandle h) {
    if (h.index >= slots_.size()) return nullptr;
    Slot& s = slots_[h.index];
    return (s.live && s.generation == h.generation) ? &*s.value : nullptr;
  }
  const T* get(SlotHandle h) const { return const_cast<GenerationalPool*>(this)->get(h); }

  /// Frees the slot; its generation advances so older handles stop resolving.
  bool erase(SlotHandle h) {
    if (!get(h)) return false;
    Slot& s = slots_[h.index];
    s.value.reset();
    s.live = false;
    ++s.generation;
    free_.push_back(h.index);
    --live_count_;
    return true;
  }

  std::size_t size() const { return live_count_; }

  /// Visits live slots in index order (deterministic).
  template <typename F>
  void forEach(F&& f) {
    for (std::uint32_t i = 0; i < slots_.size(); ++i)
      if (slots_[i].live) f(SlotHandle{i, slots_[i].generation}, *slots_[i].value);
  }

 private:
  struct Slot {
    std::optional<T> value;
    std::uint32_t generation = 1;
    bool live = false;
  };
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> free_;
  std::size_t live_count_ = 0;
};

}  // namespace zonesim
