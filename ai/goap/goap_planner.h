#pragma once
// Goal-oriented action planning: a world state is up to 64 boolean facts; actions have
// preconditions and effects on some facts and a cost; A* over world states finds the cheapest
// action sequence that makes the goal's facts true. The heuristic (0 when the goal holds, the
// cheapest action's cost otherwise) is admissible, so plans are cheapest.

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace zonesim::ai {

/// A partial assignment of facts: the facts in `mask` must equal their bit in `values`.
struct FactSet {
  std::uint64_t mask = 0;    ///< which facts are constrained
  std::uint64_t values = 0;  ///< their required or resulting values
  /// True when `state` agrees with every constrained fact.
  bool satisfiedBy(std::uint64_t state) const { return (state & mask) == (values & mask); }
  /// `state` with the constrained facts overwritten.
  std::uint64_t applyTo(std::uint64_t state) const { return (state & ~mask) | (values & mask); }
};

/// An action an agent can take.
struct GoapAction {
  std::string name;       ///< for plans and logs
  FactSet preconditions;  ///< must hold before
  FactSet effects;        ///< hold after
  double cost = 1.0;      ///< positive
};

/// Cheapest-plan search over world states, reusable across queries.
class GoapPlanner {
 public:
  /// Adds a fact name and returns its bit index (at most 64 facts).
  int addFact(const std::string& name);
  /// Bit index of a fact, or -1.
  int fact(const std::string& name) const;
  /// Adds an action and returns its index.
  int addAction(GoapAction action);
  /// The actions, by index.
  const std::vector<GoapAction>& actions() const { return actions_; }
  /// Cheapest sequence of action indices from `start` to a state satisfying `goal`; false when
  /// none is found within `max_expansions` states.
  bool plan(std::uint64_t start, const FactSet& goal, std::vector<int>& out, double* cost = nullptr,
            int max_expansions = 100000);

 private:
  struct Record {
    std::uint64_t state;
    double g;
    int parent;
    int action;
    bool closed;
  };
  struct HeapEntry {
    double f;
    double g;
    int record;
  };

  std::vector<std::string> facts_;
  std::vector<GoapAction> actions_;
  std::vector<Record> records_;
  std::unordered_map<std::uint64_t, int> index_;  // looked up only, never iterated
  std::vector<HeapEntry> heap_;
};

}  // namespace zonesim::ai
