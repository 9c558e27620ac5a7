#include "topologies/plausibility.h"

#include <cmath>

namespace zonesim::topo {

namespace {

double planar(const dr::V3& v) {
  return std::hypot(v.x, v.z);
}
dr::V3 minus(const dr::V3& a, const dr::V3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
bool finite(const dr::V3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

const char* violationName(Violation v) {
  switch (v) {
    case Violation::None:
      return "none";
    case Violation::NonFinite:
      return "non_finite";
    case Violation::Speed:
      return "speed";
    case Violation::Teleport:
      return "teleport";
    case Violation::Acceleration:
      return "acceleration";
    case Violation::StaleTick:
      return "stale_tick";
    case Violation::HitOutOfReach:
      return "hit_out_of_reach";
    case Violation::Count:
      break;
  }
  return "?";
}

Violation PlausibilityChecker::judge(const Accepted* last, std::uint64_t tick, const dr::V3& pos,
                                     const dr::V3& vel) const {
  if (!finite(pos) || !finite(vel)) return Violation::NonFinite;
  if (planar(vel) > limits_.max_speed + limits_.velocity_slack_m_s) return Violation::Speed;
  if (last == nullptr) return Violation::None;  // the first state is the reference
  if (tick <= last->tick) return Violation::StaleTick;
  double elapsed = double(tick - last->tick) * dt_;
  if (planar(minus(pos, last->pos)) > limits_.max_speed * elapsed + limits_.position_slack_m)
    return Violation::Teleport;
  if (planar(minus(vel, last->vel)) >
      limits_.max_acceleration * elapsed + limits_.velocity_slack_m_s)
    return Violation::Acceleration;
  return Violation::None;
}

Violation PlausibilityChecker::count(std::uint32_t player, Violation v) {
  if (v == Violation::None) return v;
  ++counts_[std::size_t(v)];
  ++rejected_[player];
  return v;
}

bool PlausibilityChecker::probation(std::uint32_t player, Violation v, const Accepted& claim) {
  if (limits_.probation_ticks == 0) return false;
  if (v != Violation::Teleport && v != Violation::Acceleration) {  // impossible in itself
    candidates_.erase(player);
    return false;
  }
  auto it = candidates_.find(player);
  Violation since = it == candidates_.end()
                        ? Violation::Teleport
                        : judge(&it->second.newest, claim.tick, claim.pos, claim.vel);
  if (since == Violation::StaleTick) return false;
  if (since != Violation::None) {
    candidates_[player] = {claim.tick, claim};  // a new trajectory starts here
    return false;
  }
  it->second.newest = claim;
  return claim.tick - it->second.since >= limits_.probation_ticks;
}

Violation PlausibilityChecker::checkState(std::uint32_t player, std::uint64_t tick,
                                          const dr::V3& pos, const dr::V3& vel) {
  auto it = last_.find(player);
  Violation v = judge(it == last_.end() ? nullptr : &it->second, tick, pos, vel);
  if (v == Violation::StaleTick) return count(player, v);  // a late duplicate says nothing of now
  bool reanchor = v != Violation::None && probation(player, v, {tick, pos, vel});
  if (v == Violation::None || reanchor) {
    last_[player] = {tick, pos, vel};
    distrusted_.erase(player);
    candidates_.erase(player);
    if (reanchor) ++reanchored_[player];
    return Violation::None;
  }
  distrusted_.insert(player);
  return count(player, v);
}

Violation PlausibilityChecker::checkHit(std::uint32_t attacker, const dr::V3& attacker_pos,
                                        const dr::V3& target_pos) {
  if (!finite(attacker_pos) || !finite(target_pos)) return count(attacker, Violation::NonFinite);
  bool reach =
      planar(minus(attacker_pos, target_pos)) <= limits_.hit_reach + limits_.position_slack_m;
  return count(attacker, reach ? Violation::None : Violation::HitOutOfReach);
}

std::uint64_t PlausibilityChecker::rejectedOf(std::uint32_t player) const {
  auto it = rejected_.find(player);
  return it == rejected_.end() ? 0 : it->second;
}

std::uint64_t PlausibilityChecker::reanchoredOf(std::uint32_t player) const {
  auto it = reanchored_.find(player);
  return it == reanchored_.end() ? 0 : it->second;
}

std::uint64_t PlausibilityChecker::rejected() const {
  std::uint64_t n = 0;
  for (std::size_t i = 1; i < counts_.size(); ++i) n += counts_[i];
  return n;
}

}  // namespace zonesim::topo
