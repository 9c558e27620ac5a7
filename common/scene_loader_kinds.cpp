// The scene's `clients.kinds` (docs/scene-format.md): which player kinds the fleet mixes, each
// with its speed, nimbus, share and, for flyers, height.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "common/scene.h"
#include "common/scene_loader_node.h"

namespace zonesim {

namespace {

// Shares are fractions typed by hand (0.7, 0.2, 0.1 sum to 0.9999999999999999 in doubles).
constexpr double kShareTolerance = 1e-6;

std::string allowedKinds() {
  std::string out;
  for (std::string_view n : kPlayerKindNames) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

PlayerKind readKind(PlayerKindId id, const SceneNode& node, const Scene& scene) {
  SceneMap m = node.map({"speed", "nimbus", "height", "share"});
  PlayerKind k{id, scene.clients.speed, scene.clients.nimbus, 0, 0};
  m.read("speed", k.speed, Limit::atLeast(0));
  m.read("nimbus", k.nimbus, Limit::above(0));
  k.share = m.required("share").number(Limit::between(0, 1));
  if (id != PlayerKindId::Flyer) {
    if (m.optional("height")) m.failAt("height", "only flyers have a height");
    return k;
  }
  // A flyer holds its height above the ground, which must leave it inside the world box.
  k.height = m.required("height").number(Limit::above(0));
  double ground = scene.world.min.y, top = scene.world.max.y;
  if (ground + k.height > top) {
    m.failAt("height", formatNumber(k.height) + " m above the ground is outside the world (y in [" +
                           formatNumber(ground) + ", " + formatNumber(top) + "])");
  }
  return k;
}

}  // namespace

void readPlayerKinds(const SceneMap& clients, Scene& scene) {
  std::optional<SceneNode> node = clients.optional("kinds");
  if (!node) return;
  std::vector<PlayerKind> kinds;
  double total = 0;
  for (const auto& [name, value] : node->entries()) {
    std::optional<PlayerKindId> id = playerKindNamed(name);
    if (!id) value.fail("unknown kind '" + name + "' (allowed: " + allowedKinds() + ")");
    kinds.push_back(readKind(*id, value, scene));
    total += kinds.back().share;
  }
  if (kinds.empty()) node->fail("lists no kind (allowed: " + allowedKinds() + ")");
  if (std::fabs(total - 1) > kShareTolerance)
    // Shown to six places: the sum of 0.7 and 0.2 reads 0.9, as typed, not 0.8999999999999999.
    node->fail("shares sum to " + formatNumber(std::round(total * 1e6) / 1e6) + ", not 1");
  std::sort(kinds.begin(), kinds.end(),
            [](const PlayerKind& a, const PlayerKind& b) { return a.id < b.id; });
  scene.clients.kinds = std::move(kinds);
}

}  // namespace zonesim
