#pragma once
// The scene's `interactions` key: what entities do to each other across zone borders, by
// message (zone_node/systems/interactions.h, zone_node/cluster/entity_mail.h).

#include <array>
#include <vector>

namespace zonesim {

/// NPCs hit whoever is nearest within reach (another NPC or an avatar, in this zone or a
/// neighbour's); avatars hand items to the nearest other avatar. Every hit and gift is a
/// message to the target's owner, applied there exactly once.
struct InteractionSettings {
  bool enabled = false;        ///< on when the scene has the section
  double hit_reach = 1.5;      ///< m: an NPC hits the nearest other entity this close
  double hit_every_s = 1.0;    ///< seconds between one NPC's hits
  int hit_damage = 25;         ///< health points a hit takes (health is 0..100)
  double knockback = 0.5;      ///< m/s a hit adds to its target's velocity, away from the hitter
  double gift_reach = 4.0;     ///< m: an avatar hands an item to the nearest other avatar this close
  double gift_every_s = 2.0;   ///< seconds between one avatar's gifts
  int items_per_avatar = 10;   ///< items a new avatar holds
  /// Unique items lying on the ground at these [x, z]: the nearest NPC or avatar within
  /// pickup_reach takes one, as its owner decides (a contest goes to the nearest claimant, the
  /// lowest id on a tie); it then counts among the taker's items.
  std::vector<std::array<double, 2>> items;
  double pickup_reach = 1.0;  ///< m
};

}  // namespace zonesim
