#pragma once
// Whether another player's claimed state could be true: the check a client-hosted game's host
// runs on what its clients claim, and every peer runs on every other peer. A state is judged
// against the last one accepted from the same player, by the sample ticks both carry (so a
// late datagram is not mistaken for a jump); a rejected state is not remembered, so a player
// who teleported keeps being rejected until it comes back within reach of where it was seen,
// or, with a probation, until its claims since the jump have been plausible among themselves
// for probation_ticks: the judge then re-anchors on them (it shows the player where it now is
// rather than frozen where it was last believed; the jump itself stays rejected and counted).
// Hit claims are judged by the distance between where the judge sees the two players.

#include <array>
#include <cstdint>
#include <map>
#include <set>

#include "dr/dr_state.h"

namespace zonesim::topo {

/// The movement rules every player is held to (the scene's avatar speed and acceleration).
struct MovementLimits {
  double max_speed = 5;          ///< m/s on the ground plane
  double max_acceleration = 24;  ///< m/s^2 (zone::kAvatarAccel)
  double hit_reach = 1.5;        ///< m between attacker and target
  /// Slack for the codec's quantisation (half a step a field) and float rounding: a real
  /// move may exceed the limits by this much, so honest players are never rejected.
  double position_slack_m = 0.05;
  double velocity_slack_m_s = 0.05;
  /// Ticks of mutually plausible states after a teleport or acceleration violation before the
  /// judge re-anchors on them (0: never; a state too fast or not finite restarts it).
  std::uint64_t probation_ticks = 0;
};

/// Why a claim was rejected.
enum class Violation : std::uint8_t {
  None,
  NonFinite,      ///< NaN or infinity anywhere
  Speed,          ///< the claimed velocity is faster than max_speed
  Teleport,       ///< moved further than max_speed allows since the last accepted state
  Acceleration,   ///< velocity changed faster than max_acceleration allows
  StaleTick,      ///< not newer than the last accepted state
  HitOutOfReach,  ///< a hit claimed on a target out of hit_reach
  Count
};

/// Stable snake_case name used in logs and summaries.
const char* violationName(Violation v);

/// Rejections per reason.
using ViolationCounts = std::array<std::uint64_t, std::size_t(Violation::Count)>;

class PlausibilityChecker {
 public:
  PlausibilityChecker(const MovementLimits& limits, double dt) : limits_(limits), dt_(dt) {}

  /// Judges player's state sampled at tick; accepted states become the reference.
  Violation checkState(std::uint32_t player, std::uint64_t tick, const dr::V3& pos,
                       const dr::V3& vel);
  /// Judges a hit claimed by attacker, from where the judge sees it, at a target.
  Violation checkHit(std::uint32_t attacker, const dr::V3& attacker_pos, const dr::V3& target_pos);

  /// Whether the newest state player claimed was rejected: the judge shows it where it was
  /// last believed, so it cannot judge a hit on it.
  bool distrusts(std::uint32_t player) const { return distrusted_.count(player) != 0; }
  /// Rejections so far, per reason (index Violation::None is unused).
  const ViolationCounts& counts() const { return counts_; }
  /// Rejections of one player's states and hits.
  std::uint64_t rejectedOf(std::uint32_t player) const;
  std::uint64_t rejected() const;
  /// Times the judge re-anchored on a player after its probation.
  std::uint64_t reanchoredOf(std::uint32_t player) const;

 private:
  struct Accepted {
    std::uint64_t tick;
    dr::V3 pos, vel;
  };
  Violation judge(const Accepted* last, std::uint64_t tick, const dr::V3& pos,
                  const dr::V3& vel) const;
  Violation count(std::uint32_t player, Violation v);
  // A rejected player's claims since its jump: is it on probation long enough to re-anchor?
  bool probation(std::uint32_t player, Violation v, const Accepted& claim);

  MovementLimits limits_;
  double dt_;
  std::map<std::uint32_t, Accepted> last_;
  struct Candidate {
    std::uint64_t since;  // tick of the first claim of the trajectory
    Accepted newest;
  };
  std::map<std::uint32_t, Candidate> candidates_;
  std::map<std::uint32_t, std::uint64_t> reanchored_;
  std::map<std::uint32_t, std::uint64_t> rejected_;
  std::set<std::uint32_t> distrusted_;
  ViolationCounts counts_{};
};

}  // namespace zonesim::topo
