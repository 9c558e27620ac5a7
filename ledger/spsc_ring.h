#pragma once
// A bounded single-producer single-consumer ring: push and pop never block and never allocate
// (slots are made once). The committer's two queues: tick thread -> worker and back.

#include <atomic>
#include <cstddef>
#include <new>
#include <optional>
#include <utility>
#include <vector>

namespace zonesim::ledger {

template <typename T>
class SpscRing {
 public:
  explicit SpscRing(std::size_t capacity) : slots_(capacity + 1) {}

  /// Producer side; false if full.
  bool push(T value) {
    std::size_t head = head_.load(std::memory_order_relaxed);
    std::size_t next = advance(head);
    if (next == tail_.load(std::memory_order_acquire)) return false;
    slots_[head] = std::move(value);
    head_.store(next, std::memory_order_release);
    return true;
  }

  /// Consumer side; nothing if empty.
  std::optional<T> pop() {
    std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return std::nullopt;
    std::optional<T> value(std::move(slots_[tail]));
    tail_.store(advance(tail), std::memory_order_release);
    return value;
  }

 private:
  std::size_t advance(std::size_t i) const { return i + 1 == slots_.size() ? 0 : i + 1; }

  std::vector<T> slots_;
  // Apart, so that producer and consumer do not share a cache line.
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
};

}  // namespace zonesim::ledger
