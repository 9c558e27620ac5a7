#pragma once
// A state machine defined by data: named inputs, states, and per state an ordered list of
// transitions, each guarded by comparisons of inputs with constants. States may nest
// (hierarchical machines): a composite state holds substates and enters its initial one; an
// outer state's transitions take priority over its substates'. Loaded from YAML with file:line
// errors; names are resolved to indices once, so a step compares numbers only.

#include <cstdint>
#include <string>
#include <vector>

namespace zonesim::ai {

/// Comparison operator of a condition.
enum class CompareOp { Less, LessEqual, Greater, GreaterEqual, Equal, NotEqual };

/// `inputs[input] op value`.
struct Condition {
  int input = 0;                   ///< index into the machine's inputs
  CompareOp op = CompareOp::Less;  ///< comparison
  double value = 0.0;              ///< constant compared with
};

/// A guarded edge; it fires when all conditions hold and the state has lasted `min_ticks`.
struct TransitionDef {
  int to = 0;                         ///< target state index
  std::vector<Condition> conditions;  ///< all must hold (an empty list always holds)
  int min_ticks = 0;                  ///< dwell time before it may fire (hysteresis in time)
};

/// Deepest nesting of states a machine may have.
inline constexpr int kMaxStateDepth = 8;

/// One state: transitions are tried in order, the first that fires wins.
struct StateDef {
  std::string name;                        ///< name used in files and reports (unique)
  std::vector<TransitionDef> transitions;  ///< in priority order
  int parent = -1;                         ///< enclosing composite state, -1 at top level
  int initial_child = -1;                  ///< substate entered first, -1 for a leaf
  int depth = 0;                           ///< 0 at top level
};

/// A whole machine.
struct MachineDef {
  std::string name;                 ///< machine name
  std::vector<std::string> inputs;  ///< input names; a step gets values in this order
  std::vector<StateDef> states;     ///< all states, composite and leaf, in file order
  int initial = 0;                  ///< starting leaf state index

  /// Index of a state by name, or -1.
  int stateIndex(const std::string& name) const;
  /// The leaf entered when `state` is entered (itself for a leaf).
  int enterLeaf(int state) const;
};

/// Parses a machine from YAML text; throws ParseError naming `file` and the offending line.
MachineDef parseMachineYaml(const std::string& text, const std::string& file);
/// Reads a machine file; throws ParseError.
MachineDef loadMachineYaml(const std::string& path);

/// True when the condition holds for `inputs`.
bool holds(const Condition& c, const double* inputs);

}  // namespace zonesim::ai
