#include "ai/decision/decision_tree.h"

#include <cassert>

namespace zonesim::ai {

int DecisionTree::addLeaf(int action) {
  nodes_.push_back(Node{-1, 0.0, action, action});
  root_ = int(nodes_.size()) - 1;
  return root_;
}

int DecisionTree::addTest(int input, double threshold, int if_less, int otherwise) {
  // Children must exist already, which also rules out cycles.
  assert(input >= 0 && if_less >= 0 && otherwise >= 0 && if_less < size() && otherwise < size());
  nodes_.push_back(Node{input, threshold, if_less, otherwise});
  root_ = int(nodes_.size()) - 1;
  return root_;
}

int DecisionTree::decide(const double* inputs, int* depth) const {
  assert(root_ >= 0);
  int n = root_, tests = 0;
  while (nodes_[std::size_t(n)].input >= 0) {
    const Node& node = nodes_[std::size_t(n)];
    n = inputs[node.input] < node.threshold ? node.if_less : node.otherwise;
    ++tests;
  }
  if (depth) *depth = tests;
  return nodes_[std::size_t(n)].if_less;
}

}  // namespace zonesim::ai
