#pragma once
// Binary decision trees over numeric inputs: each inner node compares one input with a
// threshold, each leaf names an action. Nodes live in one array and children are indices, so
// a decision is a short loop without allocation or virtual calls.

#include <vector>

namespace zonesim::ai {

/// A decision tree built bottom-up: add leaves and tests, then set the root.
class DecisionTree {
 public:
  /// Adds a leaf returning `action`; returns its node index.
  int addLeaf(int action);
  /// Adds a test `inputs[input] < threshold ? if_less : otherwise`; returns its node index.
  int addTest(int input, double threshold, int if_less, int otherwise);
  /// Makes `node` the root (by default the last node added).
  void setRoot(int node) { root_ = node; }
  /// The action chosen for `inputs`; `depth`, when given, receives the tests evaluated.
  int decide(const double* inputs, int* depth = nullptr) const;
  /// Number of nodes.
  int size() const { return int(nodes_.size()); }

 private:
  struct Node {
    int input;  // -1 for a leaf
    double threshold;
    int if_less;  // child index, or the action for a leaf
    int otherwise;
  };
  std::vector<Node> nodes_;
  int root_ = -1;
};

}  // namespace zonesim::ai
