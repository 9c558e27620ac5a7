#pragma once
// Reading scene YAML with errors that say where: every value is reached through a SceneNode
// that knows its file, its 1-based line and its dotted path (`populations[1].speed`), so a
// problem anywhere becomes SceneError("file:line: field: what is wrong") in one place.
// Internal to the scene loader: yaml-cpp stays out of the public headers.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/scene_geometry.h"

namespace zonesim {

struct SceneOrigins;
struct OverlaidAt;

/// Throws SceneError formatted as "file:line: field: what".
[[noreturn]] void throwSceneError(const std::string& file, int line, const std::string& field,
                                  const std::string& what);

/// Text that reads back as the same double, without an exponent for everyday magnitudes.
std::string formatNumber(double v);

/// The interval a number must lie in; describes itself for error messages.
struct Limit {
  /// No bound on that side.
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double lo = -kInf;
  double hi = kInf;
  bool lo_open = false;  ///< lo itself excluded, e.g. dt > 0

  /// v >= lo.
  static Limit atLeast(double lo) { return {lo, kInf, false}; }
  /// v > lo.
  static Limit above(double lo) { return {lo, kInf, true}; }
  /// lo <= v <= hi.
  static Limit between(double lo, double hi) { return {lo, hi, false}; }

  /// Whether v satisfies the limit.
  bool admits(double v) const { return (lo_open ? v > lo : v >= lo) && v <= hi; }
  /// ">= 0", "> 0" or "in [0, 1]".
  std::string describe() const;
};

class SceneMap;

/// A YAML node plus where it is: file, line and dotted path.
class SceneNode {
 public:
  /// `file` and `origins` (if any) must outlive the node; `line` is 1-based.
  SceneNode(YAML::Node node, std::string path, const std::string& file, int line,
            const SceneOrigins* origins = nullptr);

  /// The document root of `file`; the line is that of its first node.
  static SceneNode root(YAML::Node node, const std::string& file);
  /// The root of a document merged from overlays: values keep the files they came from.
  static SceneNode root(YAML::Node node, const SceneOrigins& origins);

  /// 1-based line of this node in its file.
  int line() const { return line_; }

  /// Throws SceneError at this node.
  [[noreturn]] void fail(const std::string& what) const;
  /// Throws SceneError about a key of this mapping: at its value if present, else here.
  [[noreturn]] void failChild(std::string_view key, const std::string& what) const;

  /// Checks that this is a mapping whose keys are unique and all in `allowed`.
  SceneMap map(std::initializer_list<std::string_view> allowed) const;
  /// The elements of a sequence, paths `path[i]`.
  std::vector<SceneNode> items() const;
  /// Looks up a key without checking the others (to dispatch on it before map()).
  std::optional<SceneNode> peek(std::string_view key) const;
  /// The key-value pairs of a mapping with free keys (plain names, each once), in file order.
  std::vector<std::pair<std::string, SceneNode>> entries() const;
  /// The file this node was read from (as named to the parser; an overlay's for its values).
  const std::string& file() const { return *file_; }
  /// Whether the value is a scalar (a name or number, not a list or mapping).
  bool isScalar() const { return node_.IsScalar(); }
  /// Whether the value is a list.
  bool isSequence() const { return node_.IsSequence(); }
  /// An empty mapping standing in for an absent key, located at this node.
  SceneNode emptyChild(std::string_view key) const;

  /// A finite number within the limit.
  double number(Limit limit = {}) const;
  /// A whole number within the limit that fits an int.
  int integer(Limit limit = {}) const;
  /// A non-negative whole number up to 2^64 - 1.
  std::uint64_t unsignedInteger() const;
  /// Any scalar, as text.
  std::string text() const;
  /// A list [x, y, z] of finite numbers.
  SceneVec3 vec3() const;
  /// A list [min, max] of numbers within the limit, min <= max.
  std::pair<double, double> range(Limit limit = {}) const;

 private:
  const std::string& plainScalar(const char* expected) const;
  std::string describeValue() const;
  std::string childPath(std::string_view key) const;
  SceneNode child(const YAML::Node& key, const YAML::Node& value) const;
  std::optional<OverlaidAt> overlaid(const YAML::Node& value) const;

  YAML::Node node_;
  std::string path_;         ///< dotted, empty for the document root
  const std::string* file_;  ///< parseScene's argument or an overlay's, which outlive every node
  int line_;                 ///< 1-based
  const SceneOrigins* origins_;  ///< which values overlays put in; null for a plain file
};

/// A mapping already checked by SceneNode::map(); hands out its values.
class SceneMap {
 public:
  /// Wraps a node whose keys were already checked.
  explicit SceneMap(SceneNode node) : node_(std::move(node)) {}

  /// A nested optional mapping; when absent it reads as empty, so defaults apply and
  /// errors about it point at this mapping's line.
  SceneMap section(std::string_view key, std::initializer_list<std::string_view> allowed) const;
  /// The value; a missing key fails at the line of this mapping.
  SceneNode required(std::string_view key) const;
  /// The value, or nothing if the key is absent.
  std::optional<SceneNode> optional(std::string_view key) const { return node_.peek(key); }

  /// Overwrites `out` with the value if the key is present; otherwise keeps the default.
  void read(std::string_view key, double& out, Limit limit = {}) const;
  /// As above for whole numbers.
  void read(std::string_view key, int& out, Limit limit = {}) const;
  /// As above for [min, max] ranges.
  void read(std::string_view key, double& min_out, double& max_out, Limit limit = {}) const;
  /// As above for true/false.
  void read(std::string_view key, bool& out) const;
  /// The index in `names` of the key's value, or `fallback` if the key is absent; any other
  /// value fails naming the allowed ones.
  int choice(std::string_view key, std::initializer_list<std::string_view> names,
             int fallback) const;
  /// Throws SceneError about a key: at its value if present, else at this mapping.
  [[noreturn]] void failAt(std::string_view key, const std::string& what) const {
    node_.failChild(key, what);
  }

 private:
  SceneNode node_;
};

/// A point on the ground written [x, z], inside `world` (the message names it otherwise).
std::pair<double, double> groundPointXZ(const SceneNode& node, const SceneBox& world);

}  // namespace zonesim
