#include "common/scene_loader_interactions.h"

namespace zonesim {

void readInteractions(const SceneMap& root, const SceneBox& world, double halo_width,
                      InteractionSettings& in) {
  if (!root.optional("interactions")) return;
  in.enabled = true;  // a section that is there means on, unless it says enabled: false
  SceneMap m = root.section(
      "interactions", {"enabled", "hit_reach", "hit_every_s", "hit_damage", "knockback",
                       "gift_reach", "gift_every_s", "items_per_avatar", "items", "pickup_reach"});
  m.read("enabled", in.enabled);
  m.read("hit_reach", in.hit_reach, Limit::atLeast(0));
  m.read("hit_every_s", in.hit_every_s, Limit::above(0));
  m.read("hit_damage", in.hit_damage, Limit::between(0, 100));
  m.read("knockback", in.knockback, Limit::atLeast(0));
  m.read("gift_reach", in.gift_reach, Limit::atLeast(0));
  m.read("gift_every_s", in.gift_every_s, Limit::above(0));
  m.read("items_per_avatar", in.items_per_avatar, Limit::between(0, 1000000));
  m.read("pickup_reach", in.pickup_reach, Limit::above(0));
  if (std::optional<SceneNode> list = m.optional("items"))
    for (const SceneNode& item : list->items()) {
      auto [x, z] = groundPointXZ(item, world);
      in.items.push_back({x, z});
    }
  // Targets across a border are seen as ghosts, which reach only halo.width into the neighbour.
  auto withinHalo = [&](const char* key, double reach) {
    if (reach > halo_width)
      m.failAt(key, formatNumber(reach) + " m is beyond halo.width (" + formatNumber(halo_width) +
                        " m): targets across a zone border would not be seen");
  };
  withinHalo("hit_reach", in.hit_reach);
  withinHalo("gift_reach", in.gift_reach);
  withinHalo("pickup_reach", in.pickup_reach);
}

}  // namespace zonesim
