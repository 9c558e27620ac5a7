#pragma once
// Fuzzy state machines: every state is active to a degree given by a trapezoidal membership
// function of one input, and the machine's outputs (speed, aggression, ...) are the states'
// outputs blended by normalised membership. Behaviour changes gradually across a threshold
// instead of jumping, which is the point of fuzzy states.

#include <vector>

namespace zonesim::ai {

/// Trapezoid: 0 below a, rising to 1 at b, 1 until c, falling to 0 at d (a <= b <= c <= d).
struct Trapezoid {
  double a = 0, b = 0, c = 0, d = 0;  ///< corners
  /// Membership of `x`, in [0, 1].
  double operator()(double x) const;
};

/// A fuzzy machine over one set of inputs with `outputs` blended values.
class FuzzyMachine {
 public:
  /// A machine producing `outputs` values per evaluation.
  explicit FuzzyMachine(int outputs) : outputs_(outputs) {}
  /// Adds a state active as `membership(inputs[input])`, contributing `values` (one per output).
  int addState(int input, Trapezoid membership, std::vector<double> values);
  /// Fills `memberships` (one per state) and `out` (one per output, blended by normalised
  /// membership; zeros when no state is active). Returns the total membership before
  /// normalisation.
  double evaluate(const double* inputs, std::vector<double>& memberships,
                  std::vector<double>& out) const;

 private:
  struct State {
    int input;
    Trapezoid membership;
    std::vector<double> values;
  };
  int outputs_;
  std::vector<State> states_;
};

}  // namespace zonesim::ai
