#pragma once
// The next due time of each of n items (a fleet's players, logins in flight), kept so that the
// earliest is read in O(1) and an item is re-armed in O(log n): an indexed binary min-heap. A
// loop that wakes for one player then touches that player alone; a scan of every due time was
// O(n) per wake-up, and with n players the wake-ups grow with n too. Equal due times come out
// in item order, so the order is the same on every run.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace zonesim {

class DueQueue {
 public:
  /// Items 0..n-1, none armed.
  explicit DueQueue(std::size_t n);

  /// Sets item's due time, armed or not; throws std::out_of_range for an item not below n.
  void arm(std::size_t item, std::int64_t due_ns);
  /// Takes item out; nothing if it is not armed.
  void disarm(std::size_t item);
  /// Disarms every item due by now_ns and appends it to out, earliest first.
  void popDue(std::int64_t now_ns, std::vector<std::size_t>& out);

  bool armed(std::size_t item) const { return pos_.at(item) != kNone; }
  /// item's due time; INT64_MAX when it is not armed.
  std::int64_t due(std::size_t item) const { return armed(item) ? due_[item] : INT64_MAX; }
  /// The earliest due time; INT64_MAX when none is armed.
  std::int64_t nextDue() const { return heap_.empty() ? INT64_MAX : due_[heap_.front()]; }
  /// Armed items.
  std::size_t size() const { return heap_.size(); }
  bool empty() const { return heap_.empty(); }

 private:
  static constexpr std::size_t kNone = SIZE_MAX;
  bool before(std::size_t a, std::size_t b) const {
    return due_[a] != due_[b] ? due_[a] < due_[b] : a < b;
  }
  void place(std::size_t at, std::size_t item);
  void siftUp(std::size_t at);
  void siftDown(std::size_t at);
  /// Restores the order around heap slot `at` after its item changed.
  void fix(std::size_t at);

  std::vector<std::size_t> heap_;  // armed items, heap-ordered by (due, item)
  std::vector<std::size_t> pos_;   // per item, its slot in heap_ (kNone: not armed)
  std::vector<std::int64_t> due_;  // per item, its due time while armed
};

}  // namespace zonesim
