#include "common/scene_loader_overlay.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include "common/scene_loader_document.h"
#include "common/scene_loader_node.h"

namespace zonesim {
namespace {

constexpr int kMaxDepth = 8;  // overlays of overlays; deeper is surely a mistake
constexpr const char* kKey = "overlay_of";

std::optional<std::string> readText(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

int lineOf(const YAML::Node& node) {
  return std::max(node.Mark().line + 1, 1);
}

// Merges `overlay` into `base` in place: mapping into mapping key by key, anything else
// replaced; each value put in is recorded as coming from `file`.
void merge(YAML::Node base, const YAML::Node& overlay, const std::string& file,
           SceneOrigins& origins) {
  for (auto it = overlay.begin(); it != overlay.end(); ++it) {
    if (!it->first.IsScalar()) throwSceneError(file, lineOf(it->first), "", "keys must be plain names");
    const std::string& key = it->first.Scalar();
    YAML::Node mine = base[key];
    if (mine.IsMap() && it->second.IsMap()) {
      merge(mine, it->second, file, origins);
    } else {
      base[key] = it->second;
      origins.overlaid.push_back({it->second, std::make_unique<std::string>(file), lineOf(it->first)});
    }
  }
}

YAML::Node parse(const std::string& text, const std::string& file, SceneOrigins& origins,
                 std::vector<std::filesystem::path>& chain) {
  YAML::Node document = parseSceneDocument(text, file);
  if (!document.IsMap() || !document[kKey]) {
    origins.root_file = file;
    return document;
  }
  YAML::Node base_name = document[kKey];
  const int line = lineOf(base_name);
  if (!base_name.IsScalar() || base_name.Scalar().empty()) {
    throwSceneError(file, line, kKey, "expected the path of the scene this file changes");
  }
  std::filesystem::path base(base_name.Scalar());
  if (base.is_relative()) base = std::filesystem::path(file).parent_path() / base;
  base = base.lexically_normal();
  std::error_code ec;
  std::filesystem::path canonical = std::filesystem::weakly_canonical(base, ec);
  for (const std::filesystem::path& seen : chain) {
    if (seen == canonical) {
      throwSceneError(file, line, kKey, "'" + base.string() + "' is already in this chain of overlays");
    }
  }
  if (chain.size() >= kMaxDepth) {
    throwSceneError(file, line, kKey, "more than " + std::to_string(kMaxDepth) + " overlays deep");
  }
  std::optional<std::string> base_text = readText(base);
  if (!base_text) throwSceneError(file, line, kKey, "cannot open base scene '" + base.string() + "'");
  chain.push_back(canonical);
  YAML::Node merged = parse(*base_text, base.string(), origins, chain);
  if (!merged.IsMap()) throwSceneError(base.string(), lineOf(merged), "", "expected a mapping");
  document.remove(kKey);
  merge(merged, document, file, origins);
  return merged;
}

}  // namespace

std::optional<OverlaidAt> SceneOrigins::find(const YAML::Node& value) const {
  // Later overlays come last and win: search from the end.
  for (auto it = overlaid.rbegin(); it != overlaid.rend(); ++it) {
    if (it->value.is(value)) return OverlaidAt{it->file.get(), it->key_line};
  }
  return std::nullopt;
}

YAML::Node parseSceneWithOverlays(const std::string& text, const std::string& file,
                                  SceneOrigins& origins) {
  std::vector<std::filesystem::path> chain;
  std::error_code ec;
  chain.push_back(std::filesystem::weakly_canonical(file, ec));
  return parse(text, file, origins, chain);
}

}  // namespace zonesim
