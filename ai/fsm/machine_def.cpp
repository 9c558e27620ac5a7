#include "ai/fsm/machine_def.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "ai/parse_error.h"
#include "ai/text_lines.h"

namespace zonesim::ai {

int MachineDef::stateIndex(const std::string& n) const {
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (states[i].name == n) return int(i);
  }
  return -1;
}

int MachineDef::enterLeaf(int state) const {
  while (states[std::size_t(state)].initial_child >= 0)
    state = states[std::size_t(state)].initial_child;
  return state;
}

bool holds(const Condition& c, const double* inputs) {
  double v = inputs[c.input];
  switch (c.op) {
    case CompareOp::Less:
      return v < c.value;
    case CompareOp::LessEqual:
      return v <= c.value;
    case CompareOp::Greater:
      return v > c.value;
    case CompareOp::GreaterEqual:
      return v >= c.value;
    case CompareOp::Equal:
      return v == c.value;
    case CompareOp::NotEqual:
      return v != c.value;
  }
  return false;
}

namespace {

// yaml-cpp marks are 0-based; users count lines from 1.
int lineOf(const YAML::Node& n) {
  return n.Mark().line + 1;
}

[[noreturn]] void fail(const std::string& file, const YAML::Node& n, const std::string& msg) {
  throw ParseError(file, lineOf(n), msg);
}

const YAML::Node require(const std::string& file, const YAML::Node& parent, const char* key) {
  YAML::Node n = parent[key];
  if (!n) fail(file, parent, std::string("missing `") + key + "`");
  return n;
}

std::string scalar(const std::string& file, const YAML::Node& n, const char* what) {
  if (!n.IsScalar()) fail(file, n, std::string(what) + " must be a scalar");
  return n.Scalar();
}

// `input op number`, e.g. `enemy_distance < 10`.
Condition parseCondition(const std::string& file, const YAML::Node& n, const MachineDef& def) {
  std::string text = scalar(file, n, "condition");
  auto f = splitFields(text);
  if (f.size() != 3) fail(file, n, "condition must read `input op number`, got '" + text + "'");
  Condition c;
  auto it = std::find(def.inputs.begin(), def.inputs.end(), std::string(f[0]));
  if (it == def.inputs.end()) fail(file, n, "unknown input '" + std::string(f[0]) + "'");
  c.input = int(it - def.inputs.begin());
  static const std::pair<const char*, CompareOp> kOps[] = {
      {"<", CompareOp::Less},          {"<=", CompareOp::LessEqual}, {">", CompareOp::Greater},
      {">=", CompareOp::GreaterEqual}, {"==", CompareOp::Equal},     {"!=", CompareOp::NotEqual}};
  bool found = false;
  for (const auto& [sym, op] : kOps) {
    if (f[1] == sym) {
      c.op = op;
      found = true;
    }
  }
  if (!found) fail(file, n, "unknown operator '" + std::string(f[1]) + "'");
  if (!parseDouble(f[2], c.value)) fail(file, n, "bad number '" + std::string(f[2]) + "'");
  return c;
}

// Declares the states of one level (and, depth first, their substates) so that transitions
// may name any state, even one declared later.
void declareStates(const std::string& file, const YAML::Node& list, int parent, MachineDef& def,
                   std::vector<YAML::Node>& nodes) {
  if (!list.IsSequence() || list.size() == 0) fail(file, list, "states must be a non-empty list");
  int depth = parent < 0 ? 0 : def.states[std::size_t(parent)].depth + 1;
  if (depth >= kMaxStateDepth) fail(file, list, "states nest too deep");
  int first = -1;
  for (const auto& s : list) {
    if (!s.IsMap()) fail(file, s, "a state must be a mapping");
    for (const auto& kv : s) {
      std::string key = kv.first.Scalar();
      if (key != "name" && key != "transitions" && key != "substates" && key != "initial") {
        fail(file, kv.first, "unknown state key '" + key + "'");
      }
    }
    std::string name = scalar(file, require(file, s, "name"), "name");
    if (def.stateIndex(name) >= 0) fail(file, s["name"], "duplicate state '" + name + "'");
    int index = int(def.states.size());
    if (first < 0) first = index;
    StateDef sd;
    sd.name = name;
    sd.parent = parent;
    sd.depth = depth;
    def.states.push_back(std::move(sd));
    nodes.push_back(s);
    if (YAML::Node subs = s["substates"]) {
      int firstChild = int(def.states.size());
      declareStates(file, subs, index, def, nodes);
      def.states[std::size_t(index)].initial_child = firstChild;
      if (YAML::Node init = s["initial"]) {
        int child = def.stateIndex(scalar(file, init, "initial"));
        if (child < 0 || def.states[std::size_t(child)].parent != index) {
          fail(file, init, "initial '" + init.Scalar() + "' is not a substate of '" + name + "'");
        }
        def.states[std::size_t(index)].initial_child = child;
      }
    } else if (s["initial"]) {
      fail(file, s["initial"], "`initial` needs `substates`");
    }
  }
}

void parseTransitions(const std::string& file, const YAML::Node& s, MachineDef& def, int state) {
  YAML::Node list = s["transitions"];
  if (!list) return;
  if (!list.IsSequence()) fail(file, list, "`transitions` must be a list");
  for (const auto& t : list) {
    if (!t.IsMap()) fail(file, t, "a transition must be a mapping");
    for (const auto& kv : t) {
      std::string key = kv.first.Scalar();
      if (key != "to" && key != "when" && key != "min_ticks") {
        fail(file, kv.first, "unknown transition key '" + key + "'");
      }
    }
    TransitionDef td;
    YAML::Node to = require(file, t, "to");
    td.to = def.stateIndex(scalar(file, to, "to"));
    if (td.to < 0) fail(file, to, "unknown state '" + to.Scalar() + "'");
    if (YAML::Node when = t["when"]) {
      if (when.IsSequence()) {
        for (const auto& c : when) td.conditions.push_back(parseCondition(file, c, def));
      } else {
        td.conditions.push_back(parseCondition(file, when, def));
      }
    }
    if (YAML::Node m = t["min_ticks"]) {
      if (!parseInt(scalar(file, m, "min_ticks"), td.min_ticks) || td.min_ticks < 0) {
        fail(file, m, "min_ticks must be a non-negative integer");
      }
    }
    def.states[std::size_t(state)].transitions.push_back(std::move(td));
  }
}

}  // namespace

MachineDef parseMachineYaml(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ParseError(file, e.mark.line + 1, e.msg);
  }
  if (!root.IsMap()) throw ParseError(file, 1, "a machine must be a mapping");
  MachineDef def;
  def.name = scalar(file, require(file, root, "machine"), "machine");
  YAML::Node inputs = require(file, root, "inputs");
  if (!inputs.IsSequence()) fail(file, inputs, "`inputs` must be a list");
  for (const auto& in : inputs) def.inputs.push_back(scalar(file, in, "input"));

  YAML::Node states = require(file, root, "states");
  std::vector<YAML::Node> nodes;  // the YAML of each state, by state index
  declareStates(file, states, -1, def, nodes);
  for (std::size_t i = 0; i < nodes.size(); ++i) parseTransitions(file, nodes[i], def, int(i));
  if (YAML::Node init = root["initial"]) {
    def.initial = def.stateIndex(scalar(file, init, "initial"));
    if (def.initial < 0) fail(file, init, "unknown initial state '" + init.Scalar() + "'");
  }
  def.initial = def.enterLeaf(def.initial);
  return def;
}

MachineDef loadMachineYaml(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ParseError(path, 0, "cannot open machine file");
  std::stringstream text;
  text << in.rdbuf();
  return parseMachineYaml(text.str(), path);
}

}  // namespace zonesim::ai
