#include "common/due_queue.h"

#include <stdexcept>
#include <string>

namespace zonesim {

DueQueue::DueQueue(std::size_t n) : pos_(n, kNone), due_(n, INT64_MAX) {
  heap_.reserve(n);
}

void DueQueue::arm(std::size_t item, std::int64_t due_ns) {
  if (item >= pos_.size())
    throw std::out_of_range("DueQueue: item " + std::to_string(item) + " of " +
                            std::to_string(pos_.size()));
  due_[item] = due_ns;
  if (pos_[item] != kNone) {
    fix(pos_[item]);
    return;
  }
  heap_.push_back(item);
  pos_[item] = heap_.size() - 1;
  siftUp(heap_.size() - 1);
}

void DueQueue::disarm(std::size_t item) {
  std::size_t at = pos_.at(item);
  if (at == kNone) return;
  pos_[item] = kNone;
  due_[item] = INT64_MAX;
  std::size_t last = heap_.back();
  heap_.pop_back();
  if (at == heap_.size()) return;  // it was the last slot
  place(at, last);
  fix(at);
}

void DueQueue::popDue(std::int64_t now_ns, std::vector<std::size_t>& out) {
  while (!heap_.empty() && due_[heap_.front()] <= now_ns) {
    out.push_back(heap_.front());
    disarm(heap_.front());
  }
}

void DueQueue::place(std::size_t at, std::size_t item) {
  heap_[at] = item;
  pos_[item] = at;
}

void DueQueue::siftUp(std::size_t at) {
  std::size_t item = heap_[at];
  while (at > 0) {
    std::size_t parent = (at - 1) / 2;
    if (!before(item, heap_[parent])) break;
    place(at, heap_[parent]);
    at = parent;
  }
  place(at, item);
}

void DueQueue::siftDown(std::size_t at) {
  std::size_t item = heap_[at];
  for (;;) {
    std::size_t child = 2 * at + 1;
    if (child >= heap_.size()) break;
    if (child + 1 < heap_.size() && before(heap_[child + 1], heap_[child])) ++child;
    if (!before(heap_[child], item)) break;
    place(at, heap_[child]);
    at = child;
  }
  place(at, item);
}

void DueQueue::fix(std::size_t at) {
  if (at > 0 && before(heap_[at], heap_[(at - 1) / 2]))
    siftUp(at);
  else
    siftDown(at);
}

}  // namespace zonesim
