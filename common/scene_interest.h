#pragma once
// The aura/nimbus rule of the scene's `interest` key (the cell size and keyframe period are
// fields of Scene itself).

namespace zonesim {

/// The seed's aura/nimbus rule: player A receives entity B's updates when A is inside B's aura
/// (range of influence, per entity type) and B inside A's nimbus (range of interest, per
/// player: clients.nimbus, grown with the player's speed up to max_nimbus).
struct AuraNimbus {
  double npc = 100;             ///< metres
  double avatar = 150;          ///< metres
  double rigid_body = 100;      ///< metres
  double emitter = 200;         ///< metres
  double item = 100;            ///< metres: unique items lying about (interactions.items)
  double nimbus_per_speed = 4;  ///< seconds: the nimbus grows by speed * this
  double max_nimbus = 150;      ///< metres: cap of the grown nimbus
};

}  // namespace zonesim
