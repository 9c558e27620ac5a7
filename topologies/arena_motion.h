#pragma once
// How a topology node's avatar moves: the zone's own avatar rule (zone/systems/steering.h,
// kAvatarAccel), driven by a scripted input that heads for a random point of the arena and
// picks a new one every retarget period. The input is a pure function of the seed, player and
// tick, so every topology plays the same game.

#include <cstdint>

#include "common/rng.h"
#include "common/scene_geometry.h"
#include "dr/dr_state.h"

namespace zonesim::topo {

/// A desired planar motion, |move| <= 1 (the cluster's Input).
struct Move {
  double x = 0, z = 0;
};

/// Where a player starts: spread on a circle around the arena's centre, the same in every
/// topology (a host places its clients' avatars there too).
dr::V3 startPosition(const SceneBox& arena, std::uint32_t player, std::uint32_t players);

/// One player's scripted input.
class ScriptedInput {
 public:
  ScriptedInput(const SceneBox& arena, std::uint64_t seed, std::uint32_t player,
                std::uint64_t retarget_ticks);
  /// The move at this tick from the avatar's position; `changed` is set when a new target was
  /// chosen at this tick (an input event whose effect the others measure).
  Move at(std::uint64_t tick, const dr::V3& pos, bool& changed);

 private:
  SceneBox arena_;
  Pcg32 rng_;
  std::uint64_t retarget_ticks_, phase_;
  Move move_;
};

/// An avatar's kinematic state.
struct AvatarBody {
  dr::V3 pos, vel;
};

/// One tick of the zone's avatar movement toward move * max_speed.
void stepAvatar(const SceneBox& world, AvatarBody& body, const Move& move, double max_speed,
                double accel, double dt);

}  // namespace zonesim::topo
