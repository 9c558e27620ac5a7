#include "ai/goap/goap_planner.h"

#include <algorithm>
#include <cassert>

namespace zonesim::ai {

int GoapPlanner::addFact(const std::string& name) {
  assert(facts_.size() < 64 && fact(name) < 0);
  facts_.push_back(name);
  return int(facts_.size()) - 1;
}

int GoapPlanner::fact(const std::string& name) const {
  auto it = std::find(facts_.begin(), facts_.end(), name);
  return it == facts_.end() ? -1 : int(it - facts_.begin());
}

int GoapPlanner::addAction(GoapAction action) {
  assert(action.cost > 0);
  actions_.push_back(std::move(action));
  return int(actions_.size()) - 1;
}

bool GoapPlanner::plan(std::uint64_t start, const FactSet& goal, std::vector<int>& out,
                       double* cost, int max_expansions) {
  out.clear();
  records_.clear();
  index_.clear();
  heap_.clear();
  double minCost = 0.0;
  for (std::size_t i = 0; i < actions_.size(); ++i) {
    minCost = i == 0 ? actions_[i].cost : std::min(minCost, actions_[i].cost);
  }
  auto h = [&](std::uint64_t s) { return goal.satisfiedBy(s) ? 0.0 : minCost; };
  // Lower f first, then deeper g, then the older record: ties never depend on hashing.
  auto after = [](const HeapEntry& a, const HeapEntry& b) {
    if (a.f != b.f) return a.f > b.f;
    if (a.g != b.g) return a.g < b.g;
    return a.record > b.record;
  };
  records_.push_back(Record{start, 0.0, -1, -1, false});
  index_[start] = 0;
  heap_.push_back(HeapEntry{h(start), 0.0, 0});
  int expansions = 0;
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), after);
    HeapEntry top = heap_.back();
    heap_.pop_back();
    if (records_[std::size_t(top.record)].closed || top.g > records_[std::size_t(top.record)].g) {
      continue;
    }
    records_[std::size_t(top.record)].closed = true;
    const std::uint64_t state = records_[std::size_t(top.record)].state;
    if (goal.satisfiedBy(state)) {
      if (cost) *cost = top.g;
      for (int r = top.record; records_[std::size_t(r)].parent >= 0;
           r = records_[std::size_t(r)].parent) {
        out.push_back(records_[std::size_t(r)].action);
      }
      std::reverse(out.begin(), out.end());
      return true;
    }
    if (++expansions > max_expansions) return false;
    for (std::size_t a = 0; a < actions_.size(); ++a) {
      const GoapAction& act = actions_[a];
      if (!act.preconditions.satisfiedBy(state)) continue;
      std::uint64_t next = act.effects.applyTo(state);
      if (next == state) continue;
      double g = top.g + act.cost;
      auto [it, inserted] = index_.try_emplace(next, int(records_.size()));
      if (inserted) {
        records_.push_back(Record{next, g, top.record, int(a), false});
      } else {
        Record& r = records_[std::size_t(it->second)];
        if (r.closed || r.g <= g) continue;
        r.g = g;
        r.parent = top.record;
        r.action = int(a);
      }
      heap_.push_back(HeapEntry{g + h(next), g, it->second});
      std::push_heap(heap_.begin(), heap_.end(), after);
    }
  }
  return false;
}

}  // namespace zonesim::ai
