#include "topologies/arena_motion.h"

#include <algorithm>
#include <cmath>

#include "zone_node/systems/avatar_movement.h"
#include "zone_node/systems/steering.h"

namespace zonesim::topo {

namespace {
// Streams of the scripts, apart from the zone's entity and duel streams.
constexpr std::uint64_t kScriptStreamBase = 0x70b0'0000'0000ull;
// Targets keep this far from the walls, so a player heading for one is not stopped by a wall
// (which would change its velocity without an input).
constexpr double kWallMargin = 2.0;
}  // namespace

ScriptedInput::ScriptedInput(const SceneBox& arena, std::uint64_t seed, std::uint32_t player,
                             std::uint64_t retarget_ticks)
    : arena_(arena),
      rng_(seed, kScriptStreamBase + player),
      retarget_ticks_(retarget_ticks == 0 ? 1 : retarget_ticks),
      phase_(std::uint64_t(player) * 7 % retarget_ticks_) {}

Move ScriptedInput::at(std::uint64_t tick, const dr::V3& pos, bool& changed) {
  changed = tick % retarget_ticks_ == phase_ || (tick == 0);
  if (!changed) return move_;
  double tx = rng_.uniform(arena_.min.x + kWallMargin, arena_.max.x - kWallMargin);
  double tz = rng_.uniform(arena_.min.z + kWallMargin, arena_.max.z - kWallMargin);
  double dx = tx - pos.x, dz = tz - pos.z, n = std::hypot(dx, dz);
  move_ = n < 1e-6 ? Move{} : Move{dx / n, dz / n};
  return move_;
}

dr::V3 startPosition(const SceneBox& arena, std::uint32_t player, std::uint32_t players) {
  double cx = 0.5 * (arena.min.x + arena.max.x), cz = 0.5 * (arena.min.z + arena.max.z);
  double r = 0.35 * std::min(arena.max.x - arena.min.x, arena.max.z - arena.min.z);
  double a = 2 * M_PI * double(player) / double(players == 0 ? 1 : players);
  return {cx + r * std::cos(a), arena.min.y, cz + r * std::sin(a)};
}

void stepAvatar(const SceneBox& world, AvatarBody& body, const Move& move, double max_speed,
                double accel, double dt) {
  Vec3 pos(body.pos.x, body.pos.y, body.pos.z), vel(body.vel.x, body.vel.y, body.vel.z);
  Vec3 desired(move.x * max_speed, 0.0, move.z * max_speed);
  zone::steerAndIntegrate(pos, vel, desired, accel, dt);
  zone::keepOnGround(world, pos, vel);
  body.pos = {pos.x(), pos.y(), pos.z()};
  body.vel = {vel.x(), vel.y(), vel.z()};
}

}  // namespace zonesim::topo
