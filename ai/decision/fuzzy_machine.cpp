#include "ai/decision/fuzzy_machine.h"

#include <cassert>

namespace zonesim::ai {

double Trapezoid::operator()(double x) const {
  if (x < a || x > d) return 0.0;
  if (x < b) return b > a ? (x - a) / (b - a) : 1.0;
  if (x <= c) return 1.0;
  return d > c ? (d - x) / (d - c) : 1.0;
}

int FuzzyMachine::addState(int input, Trapezoid membership, std::vector<double> values) {
  assert(int(values.size()) == outputs_);
  states_.push_back(State{input, membership, std::move(values)});
  return int(states_.size()) - 1;
}

double FuzzyMachine::evaluate(const double* inputs, std::vector<double>& memberships,
                              std::vector<double>& out) const {
  memberships.assign(states_.size(), 0.0);
  out.assign(std::size_t(outputs_), 0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < states_.size(); ++i) {
    memberships[i] = states_[i].membership(inputs[states_[i].input]);
    total += memberships[i];
  }
  if (total <= 0.0) return 0.0;
  for (std::size_t i = 0; i < states_.size(); ++i) {
    double w = memberships[i] / total;
    for (int k = 0; k < outputs_; ++k) out[std::size_t(k)] += w * states_[i].values[std::size_t(k)];
  }
  return total;
}

}  // namespace zonesim::ai
