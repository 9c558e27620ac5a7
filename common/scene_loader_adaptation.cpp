#include "common/scene_loader_adaptation.h"

#include <filesystem>
#include <fstream>
#include <optional>
#include <tuple>

namespace zonesim {

namespace {

void readDuels(const SceneMap& m, const SceneBox& world, AdaptationSettings& a) {
  SceneNode list = m.required("duels");
  for (const SceneNode& item : list.items()) {
    SceneMap duel = item.map({"skill", "at", "count"});
    DuelSpec spec;
    spec.skill = duel.required("skill").number(Limit::between(0, 1));
    std::tie(spec.x, spec.z) = groundPointXZ(duel.required("at"), world);
    int count = 1;
    duel.read("count", count, Limit::between(1, 10000));
    a.duels.insert(a.duels.end(), std::size_t(count), spec);
  }
  if (a.duels.empty()) list.fail("needs at least one duel");
}

// Only whether it opens (relative to the file that names it, an overlay's if it changed it):
// the zone parses it (ai/adapt/model_file.h names the file's own line).
void readModelPath(const SceneMap& m, AdaptationSettings& a) {
  std::optional<SceneNode> node = m.optional("model");
  if (!node) {
    if (a.mode == AdaptationSettings::Mode::Model)
      m.failAt("model", "required with mode: model (a file written by adapt_train)");
    return;
  }
  std::filesystem::path path(node->text());
  if (path.empty()) node->fail("must not be empty");
  if (path.is_relative()) path = std::filesystem::path(node->file()).parent_path() / path;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec) || !std::ifstream(path))
    node->fail("cannot open model file '" + path.string() + "'");
  a.model = path.lexically_normal().string();
}

}  // namespace

void readAdaptation(const SceneMap& root, const SceneBox& world, AdaptationSettings& a) {
  if (!root.optional("adaptation")) return;
  a.enabled = true;  // a section that is there means on, unless it says enabled: false
  SceneMap m = root.section("adaptation", {"enabled", "mode", "model", "target_win_rate",
                                           "max_step", "rubber_band", "duels"});
  m.read("enabled", a.enabled);
  a.mode = AdaptationSettings::Mode(m.choice("mode", {"off", "rubber_band", "model"}, int(a.mode)));
  readModelPath(m, a);
  // Beyond these a duel cannot be balanced: the gentlest and deadliest NPCs bound the outcome.
  m.read("target_win_rate", a.target_win_rate, Limit::between(0.05, 0.95));
  m.read("max_step", a.max_step, Limit{0, 1, true});
  SceneMap band = m.section("rubber_band", {"window", "gain"});
  band.read("window", a.band_window, Limit::between(1, 1000));
  band.read("gain", a.band_gain, Limit::between(0, 10));
  readDuels(m, world, a);
}

}  // namespace zonesim
