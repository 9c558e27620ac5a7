#include "common/scene_loader_node.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <system_error>
#include <tuple>

#include "common/scene.h"
#include "common/scene_loader_overlay.h"

namespace zonesim {
namespace {

// YAML allows a leading '+' on numbers; from_chars does not.
std::string_view withoutPlus(std::string_view s) {
  return (s.size() > 1 && s[0] == '+') ? s.substr(1) : s;
}

template <typename T>
bool parseWhole(std::string_view s, T& out) {
  s = withoutPlus(s);
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

std::string joined(std::initializer_list<std::string_view> names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

}  // namespace

void throwSceneError(const std::string& file, int line, const std::string& field,
                     const std::string& what) {
  throw SceneError(file + ":" + std::to_string(line) + ": " + (field.empty() ? "document" : field) +
                   ": " + what);
}

std::string formatNumber(double v) {
  // Plain digits for everyday magnitudes ("1000000", not "1e+06"), exponents beyond them.
  double mag = std::fabs(v);
  auto format = (mag == 0 || (mag >= 1e-4 && mag < 1e15)) ? std::chars_format::fixed
                                                          : std::chars_format::general;
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, format);
  return ec == std::errc() ? std::string(buf, end) : std::string("?");
}

std::string Limit::describe() const {
  std::string low = formatNumber(lo), high = formatNumber(hi);
  if (hi == kInf) return (lo_open ? "> " : ">= ") + low;
  if (lo == -kInf) return "<= " + high;
  return (lo_open ? "in (" : "in [") + low + ", " + high + "]";
}

SceneNode::SceneNode(YAML::Node node, std::string path, const std::string& file, int line,
                     const SceneOrigins* origins)
    : node_(std::move(node)),
      path_(std::move(path)),
      file_(&file),
      line_(line),
      origins_(origins) {}

SceneNode SceneNode::root(YAML::Node node, const std::string& file) {
  int line = std::max(node.Mark().line + 1, 1);
  return SceneNode(std::move(node), "", file, line);
}

std::optional<OverlaidAt> SceneNode::overlaid(const YAML::Node& value) const {
  return origins_ ? origins_->find(value) : std::nullopt;
}

SceneNode SceneNode::root(YAML::Node node, const SceneOrigins& origins) {
  int line = std::max(node.Mark().line + 1, 1);
  return SceneNode(std::move(node), "", origins.root_file, line, &origins);
}

void SceneNode::fail(const std::string& what) const {
  throwSceneError(*file_, line_, path_, what);
}

void SceneNode::failChild(std::string_view key, const std::string& what) const {
  if (std::optional<SceneNode> value = peek(key)) value->fail(what);
  throwSceneError(*file_, line_, childPath(key), what);
}

std::string SceneNode::childPath(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

SceneNode SceneNode::emptyChild(std::string_view key) const {
  return SceneNode(YAML::Node(YAML::NodeType::Map), childPath(key), *file_, line_, origins_);
}

SceneNode SceneNode::child(const YAML::Node& key, const YAML::Node& value) const {
  // yaml-cpp marks an empty value at the next token and an alias at its anchor; the key's
  // line is where the user looks in both cases.
  // A value an overlay put in sits under a key node of another file: the overlay's key line.
  std::optional<OverlaidAt> overlay = overlaid(value);
  int key_line = overlay ? overlay->key_line : key.Mark().line + 1;
  int value_line = value.Mark().line + 1;
  int line = (value.IsNull() || value_line < key_line) ? key_line : value_line;
  return SceneNode(value, childPath(key.Scalar()), overlay ? *overlay->file : *file_, line,
                   origins_);
}

std::string SceneNode::describeValue() const {
  switch (node_.Type()) {
    case YAML::NodeType::Sequence:
      return "a list of " + std::to_string(node_.size()) + " items";
    case YAML::NodeType::Map:
      return "a mapping";
    case YAML::NodeType::Scalar:
      if (node_.Tag() == "!") return "the quoted string \"" + node_.Scalar() + "\"";
      return "'" + node_.Scalar() + "'";
    default:
      return "nothing";
  }
}

SceneMap SceneNode::map(std::initializer_list<std::string_view> allowed) const {
  if (!node_.IsMap()) fail("expected a mapping, got " + describeValue());
  std::vector<std::pair<std::string, int>> seen;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    int key_line = it->first.Mark().line + 1;
    if (!it->first.IsScalar()) {
      throwSceneError(*file_, key_line, path_, "keys must be plain names");
    }
    const std::string& key = it->first.Scalar();
    std::string path = childPath(key);
    for (const auto& [name, line] : seen) {
      if (name == key) {
        throwSceneError(*file_, key_line, path,
                        "duplicate key (first given on line " + std::to_string(line) + ")");
      }
    }
    bool known = false;
    for (std::string_view name : allowed) known = known || name == key;
    if (!known) {
      std::optional<OverlaidAt> overlay = overlaid(it->second);
      throwSceneError(overlay ? *overlay->file : *file_, overlay ? overlay->key_line : key_line,
                      path, "unknown key (allowed: " + joined(allowed) + ")");
    }
    seen.emplace_back(key, key_line);
  }
  return SceneMap(*this);
}

std::vector<SceneNode> SceneNode::items() const {
  if (!node_.IsSequence()) fail("expected a list, got " + describeValue());
  std::vector<SceneNode> out;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    YAML::Node item = node_[i];
    int line = item.IsNull() ? line_ : std::max(item.Mark().line + 1, line_);
    out.emplace_back(item, path_ + "[" + std::to_string(i) + "]", *file_, line, origins_);
  }
  return out;
}

std::vector<std::pair<std::string, SceneNode>> SceneNode::entries() const {
  if (!node_.IsMap()) fail("expected a mapping, got " + describeValue());
  std::vector<std::pair<std::string, SceneNode>> out;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    int key_line = it->first.Mark().line + 1;
    if (!it->first.IsScalar()) throwSceneError(*file_, key_line, path_, "keys must be plain names");
    for (const auto& [name, node] : out) {
      if (name == it->first.Scalar())
        throwSceneError(*file_, key_line, childPath(name),
                        "duplicate key (first given on line " + std::to_string(node.line()) + ")");
    }
    out.emplace_back(it->first.Scalar(), child(it->first, it->second));
  }
  return out;
}

std::optional<SceneNode> SceneNode::peek(std::string_view key) const {
  if (!node_.IsMap()) fail("expected a mapping, got " + describeValue());
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (it->first.IsScalar() && it->first.Scalar() == key) return child(it->first, it->second);
  }
  return std::nullopt;
}

const std::string& SceneNode::plainScalar(const char* expected) const {
  if (!node_.IsScalar() || node_.Tag() == "!") {
    fail(std::string("expected ") + expected + ", got " + describeValue());
  }
  return node_.Scalar();
}

double SceneNode::number(Limit limit) const {
  std::string_view s = withoutPlus(plainScalar("a number"));
  double v = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) {
    fail("expected a finite number, got " + describeValue());
  }
  if (!limit.admits(v)) fail("must be " + limit.describe() + ", got " + formatNumber(v));
  return v;
}

int SceneNode::integer(Limit limit) const {
  long long v = 0;
  if (!parseWhole(plainScalar("a whole number"), v)) {
    fail("expected a whole number, got " + describeValue());
  }
  if (v < INT_MIN || v > INT_MAX) fail("is too large, got " + node_.Scalar());
  if (!limit.admits(double(v))) fail("must be " + limit.describe() + ", got " + std::to_string(v));
  return int(v);
}

std::uint64_t SceneNode::unsignedInteger() const {
  const std::string& s = plainScalar("a whole number");
  std::uint64_t v = 0;
  if (!s.empty() && s[0] == '-') fail("must be >= 0, got " + s);
  if (!parseWhole(s, v)) fail("expected a whole number below 2^64, got " + describeValue());
  return v;
}

std::string SceneNode::text() const {
  if (!node_.IsScalar()) fail("expected a name, got " + describeValue());
  return node_.Scalar();
}

SceneVec3 SceneNode::vec3() const {
  if (!node_.IsSequence() || node_.size() != 3) {
    fail("expected a list [x, y, z], got " + describeValue());
  }
  std::vector<SceneNode> xyz = items();
  return {xyz[0].number(), xyz[1].number(), xyz[2].number()};
}

std::pair<double, double> SceneNode::range(Limit limit) const {
  if (!node_.IsSequence() || node_.size() != 2) {
    fail("expected a list [min, max], got " + describeValue());
  }
  std::vector<SceneNode> bounds = items();
  double lo = bounds[0].number(limit), hi = bounds[1].number(limit);
  if (lo > hi) fail("min " + formatNumber(lo) + " is greater than max " + formatNumber(hi));
  return {lo, hi};
}

SceneNode SceneMap::required(std::string_view key) const {
  std::optional<SceneNode> value = node_.peek(key);
  if (!value) node_.failChild(key, "required field is missing");
  return *value;
}

SceneMap SceneMap::section(std::string_view key,
                           std::initializer_list<std::string_view> allowed) const {
  if (std::optional<SceneNode> value = optional(key)) return value->map(allowed);
  return SceneMap(node_.emptyChild(key));
}

void SceneMap::read(std::string_view key, double& out, Limit limit) const {
  if (auto value = optional(key)) out = value->number(limit);
}

void SceneMap::read(std::string_view key, int& out, Limit limit) const {
  if (auto value = optional(key)) out = value->integer(limit);
}

void SceneMap::read(std::string_view key, double& min_out, double& max_out, Limit limit) const {
  if (auto value = optional(key)) std::tie(min_out, max_out) = value->range(limit);
}

void SceneMap::read(std::string_view key, bool& out) const {
  auto value = optional(key);
  if (!value) return;
  std::string t = value->text();
  if (t == "true")
    out = true;
  else if (t == "false")
    out = false;
  else
    value->fail("expected true or false, got '" + t + "'");
}

int SceneMap::choice(std::string_view key, std::initializer_list<std::string_view> names,
                     int fallback) const {
  auto value = optional(key);
  if (!value) return fallback;
  std::string t = value->text();
  std::string allowed;
  int i = 0;
  for (std::string_view n : names) {
    if (t == n) return i;
    allowed += (i++ ? ", " : "") + std::string(n);
  }
  value->fail("unknown value '" + t + "' (allowed: " + allowed + ")");
}

std::pair<double, double> groundPointXZ(const SceneNode& node, const SceneBox& world) {
  std::vector<SceneNode> items = node.items();
  if (items.size() != 2) node.fail("expected a point [x, z]");
  const double x = items[0].number(), z = items[1].number();
  if (x < world.min.x || x > world.max.x || z < world.min.z || z > world.max.z)
    node.fail("(" + formatNumber(x) + ", " + formatNumber(z) + ") is outside the world");
  return {x, z};
}

}  // namespace zonesim
