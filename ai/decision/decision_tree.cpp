#include "ai/decision/decision_tree.h"

#include <cassert>

namespace zonesim::ai {

int DecisionTree::addLeaf(int action) {
  nodes_.push_back(Node{-1, 0.0, action, action});
  root_ = int(nodes_.size()) - 1;
  return root_;
}

int DecisionTree::addTest(int input, double threshold, int ifLess, int otherwise) {
  // Children must exist already, which also rules out cycles.
  assert(input >= 0 && ifLess >= 0 && otherwise >= 0 && ifLess < size() && otherwise < size());
  nodes_.push_back(Node{input, threshold, ifLess, otherwise});
  root_ = int(nodes_.size()) - 1;
  return root_;
}

int DecisionTree::decide(const double* inputs, int* depth) const {
  assert(root_ >= 0);
  int n = root_, tests = 0;
  while (nodes_[std::size_t(n)].input >= 0) {
    const Node& node = nodes_[std::size_t(n)];
    n = inputs[node.input] < node.threshold ? node.ifLess : node.otherwise;
    ++tests;
  }
  if (depth) *depth = tests;
  return nodes_[std::size_t(n)].ifLess;
}

}  // namespace zonesim::ai
