#include "zone_node/systems/agent_system.h"

#include <algorithm>
#include <cmath>

#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/agent_decisions.h"
#include "zone_node/systems/agent_goap.h"
#include "zone_node/systems/crowd_lod.h"
#include "zone_node/systems/steering.h"
#include "zone_node/tick_profile.h"

namespace zonesim::zone {

namespace {

bool isAction(const AgentData& a, AgentAction action) {
  return a.action == int(action);
}

Vec3 toward(const Vec3& from, const Vec3& to, double speed) {
  Vec3 d = to - from;
  d.y() = 0;
  double n = d.norm();
  return n > 1e-9 ? Vec3(d * (speed / n)) : Vec3::Zero();
}

}  // namespace

AgentSystem::AgentSystem(const Scene& scene, ZoneMap* map)
    : scene_(scene),
      decisions_(std::make_unique<AgentDecisions>(scene)),
      goap_(std::make_unique<AgentGoapPlans>(scene.agents)),
      nav_(scene, map),
      lod_(lodOf(scene.lod)) {
  for (const AgentType& t : scene.agents.types) reach_ = std::max(reach_, t.sight);
}

AgentSystem::~AgentSystem() = default;

bool AgentSystem::active() const {
  return !scene_.agents.types.empty();
}

void AgentSystem::step(StepContext& ctx) {
  EntityStore& store = ctx.store;
  const double time = ctx.time, dt = ctx.dt;
  const auto tick = std::int64_t(ctx.tick);
  AgentTickStats stats;
  nav_.followDoors(store);
  planDecisions(store, ctx.players, ctx.tick);
  senseAgents(scene_.agents, store, ctx.ghosts, time, decides_, senses_);
  // Decide and name targets; paths are asked for here and planned below in one budgeted batch.
  for (std::size_t i = 0; i < store.size(); ++i) {
    AgentData& a = store.agent[i];
    if (a.type < 0) continue;
    ++stats.agents;
    if (!decides_.empty() && !decides_[i]) continue;  // acts on its last decision
    ++stats.decisions;
    const AgentSenses& seen = senses_[i];
    a.enemy_seen = seen.enemy_seen;
    a.enemy_x = seen.enemy.x();
    a.enemy_z = seen.enemy.z();
    a.enemy_distance = seen.value[int(AgentSense::EnemyDistance)];
    const AgentType& t = scene_.agents.types[std::size_t(a.type)];
    int before = a.transitions;
    decisions_->decide(a, senses_[i]);
    stats.transitions += std::uint64_t(a.transitions - before);
    if (pursues(a, t, senses_[i])) {
      pursue(store, i, senses_[i], tick);
      continue;
    }
    if (!isAction(a, AgentAction::Travel)) {
      // Leaving travel drops the path: travel resumes from wherever the agent is then.
      a.nav = std::int32_t(AgentNav::None);
      a.path.clear();
      continue;
    }
    double x = 0, z = 0;
    if (t.behaviour == AgentType::Behaviour::Goap) {
      if (!goap_->target(a, x, z)) {
        a.action = int(AgentAction::Idle);
        continue;
      }
    } else if (!t.goals.empty()) {
      std::tie(x, z) = t.goals[std::size_t(a.goal) % t.goals.size()];
    } else {
      a.action = int(AgentAction::Idle);
      continue;
    }
    nav_.want(store, i, x, z, t.navigate, tick);
  }
  nav_.plan(store, ctx.cluster.gather);
  for (std::size_t i = 0; i < store.size(); ++i)
    if (store.agent[i].type >= 0) move(store, i, senses_[i], dt);
  stats.paths = nav_.takeStats();
  ctx.counters.agents = stats.agents;
  ctx.counters.agent_transitions = stats.transitions;
  ctx.counters.agent_decisions = stats.decisions;
  ctx.counters.paths_planned = stats.paths.planned;
  ctx.counters.paths_queued = stats.paths.queued;
  ctx.counters.path_replans = stats.paths.replans;
  ctx.counters.path_plan_ns = stats.paths.plan_ns;
  ctx.counters.paths_audited = stats.paths.audited;
  ctx.counters.path_overhead_ppm = stats.paths.overhead_ppm;
  ctx.counters.path_overhead_max_ppm = stats.paths.overhead_max_ppm;
  ctx.counters.path_audit_ns = stats.paths.audit_ns;
  last_ = stats;
}

int AgentSystem::decisionPeriod(const Vec3& pos, std::span<const crowd::Vec2> players) const {
  const int every = scene_.agents.decide_every;
  if (!scene_.lod.enabled) return every;
  // The crowds' bands (crowd/lod.h): near a player every tick, then mid_every, then far_every.
  const crowd::LodLevel level = crowd::lodLevel(crowd::Vec2{pos.x(), pos.z()}, players, lod_);
  return std::max(every, crowd::lodPeriod(level, lod_));
}

void AgentSystem::planDecisions(const EntityStore& store, std::span<const crowd::Vec2> players,
                                std::uint64_t tick) {
  // An agent looks and decides on one tick in its period, which its id picks, so the agents
  // of a period spread evenly over its ticks; the same on every rank.
  decides_.clear();
  if (scene_.agents.decide_every == 1 && !scene_.lod.enabled) return;
  decides_.resize(store.size());
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.agent[i].type < 0) continue;
    decides_[i] =
        crowd::lodDue(store.id[i].value, std::int64_t(tick), decisionPeriod(store.pos[i], players));
  }
}

bool AgentSystem::pursues(const AgentData& a, const AgentType& t, const AgentSenses& s) const {
  // Fuzzy agents blend chase and roam headings; they keep steering.
  return nav_.hasMap() && s.enemy_seen && t.behaviour != AgentType::Behaviour::Fuzzy &&
         (isAction(a, AgentAction::Chase) || isAction(a, AgentAction::Flee));
}

void AgentSystem::pursue(EntityStore& store, std::size_t i, const AgentSenses& s,
                         std::int64_t tick) {
  AgentData& a = store.agent[i];
  const AgentType& t = scene_.agents.types[std::size_t(a.type)];
  const double px = store.pos[i].x(), pz = store.pos[i].z();
  const double ex = s.enemy.x(), ez = s.enemy.z();
  const bool going =
      a.nav == std::int32_t(AgentNav::Waiting) || a.nav == std::int32_t(AgentNav::Moving);
  const bool arrived = a.nav == std::int32_t(AgentNav::Arrived);
  const double target_to_enemy = std::hypot(a.target_x - ex, a.target_z - ez);
  double x = a.target_x, z = a.target_z;
  if (isAction(a, AgentAction::Chase)) {
    // Re-plan once the quarry has moved away from the path's end by the threshold (or at all,
    // once there).
    if (!(going && target_to_enemy <= kPursuitReplanDistance) &&
        !(arrived && target_to_enemy <= t.arrive_distance)) {
      x = ex;
      z = ez;
    }
  } else {
    // A new refuge when none is set, reached, or once the threat is nearer to it than we are.
    bool keep = going && target_to_enemy > std::hypot(a.target_x - px, a.target_z - pz);
    if (!keep) {
      crowd::Vec2 refuge = nav_.fleeTarget(px, pz, ex, ez, std::max(t.sight, 1.0));
      x = refuge.x;
      z = refuge.y;
    }
  }
  nav_.want(store, i, x, z, true, tick);
}

void AgentSystem::move(EntityStore& store, std::size_t i, const AgentSenses& s, double dt) {
  AgentData& a = store.agent[i];
  const AgentType& t = scene_.agents.types[std::size_t(a.type)];
  bool fuzzy = t.behaviour == AgentType::Behaviour::Fuzzy;
  double speed = t.speed * (fuzzy ? a.speed_factor : 1.0);
  Vec3& pos = store.pos[i];
  Vec3& vel = store.vel[i];
  Vec3 before = pos;
  Vec3 desired = Vec3::Zero();
  bool placed = false;  // the spline set the position itself
  switch (AgentAction(a.action)) {
    case AgentAction::Idle:
    case AgentAction::Attack:
    case AgentAction::Count:
      break;
    case AgentAction::Wander: {
      NpcData& npc = store.npc[i];
      Vec3 to = npc.waypoint - pos;
      to.y() = 0;
      if (to.norm() < t.arrive_distance + 0.5)
        npc.waypoint = nextWaypoint(scene_, pos, t.wander_radius, store.rng_state[i], store.id[i]);
      desired = toward(pos, npc.waypoint, speed);
      break;
    }
    case AgentAction::Chase:
    case AgentAction::Flee: {
      if (!s.enemy_seen) break;
      if (pursues(a, t, s)) {
        // On a map: along the planned path (toward the quarry, or to the refuge).
        placed = nav_.follow(store, i, speed, t.acceleration, t.arrive_distance, dt, desired);
        break;
      }
      Vec3 chase = toward(pos, s.enemy, 1.0);
      if (fuzzy) {
        // Blended: part toward (or away from) the enemy, the rest along the wander heading.
        Vec3 roam = toward(pos, store.npc[i].waypoint, 1.0);
        Vec3 mix = chase * a.approach + roam * (1.0 - std::fabs(a.approach));
        double n = mix.norm();
        desired = n > 1e-9 ? Vec3(mix * (speed / n)) : Vec3::Zero();
      } else {
        desired = chase * (isAction(a, AgentAction::Flee) ? -speed : speed);
      }
      break;
    }
    case AgentAction::Travel: {
      bool was_moving = a.nav == std::int32_t(AgentNav::Moving);
      placed = nav_.follow(store, i, speed, t.acceleration, t.arrive_distance, dt, desired);
      bool arrived = a.nav == std::int32_t(AgentNav::Arrived);
      if (arrived && was_moving) ++a.arrivals;
      if (!arrived) break;
      if (!placed) desired = Vec3::Zero();
      if (t.behaviour == AgentType::Behaviour::Goap) {
        if (goap_->work(a, dt)) a.nav = std::int32_t(AgentNav::None);
      } else {
        a.dwell += dt;
        if (a.dwell >= t.dwell_s) {
          a.dwell = 0;
          a.goal = (a.goal + 1) % std::int32_t(std::max<std::size_t>(t.goals.size(), 1));
          a.nav = std::int32_t(AgentNav::None);
        }
      }
      break;
    }
  }
  if (!placed) {
    steerAndIntegrate(pos, vel, desired, t.acceleration, dt);
    if (const ai::GridMap* grid = nav_.grid()) {
      // Walls: the step slides along them and never enters a blocked cell.
      crowd::Vec2 v{vel.x(), vel.z()};
      crowd::Vec2 at =
          crowd::slideMove(*grid, nav_.frame(), {before.x(), before.z()}, {pos.x(), pos.z()}, v);
      pos.x() = at.x;
      pos.z() = at.y;
      vel.x() = v.x;
      vel.z() = v.y;
    }
  }
  keepOnGround(scene_.world, pos, vel);
  Vec3 face = isAction(a, AgentAction::Attack) && s.enemy_seen ? Vec3(s.enemy - pos) : vel;
  store.rot[i] = facing(store.rot[i], face);
  double moved = std::hypot(pos.x() - before.x(), pos.z() - before.z()) / dt;
  updateNeeds(a, t, s, moved, dt);
}

void AgentSystem::updateNeeds(AgentData& a, const AgentType& t, const AgentSenses& s, double speed,
                              double dt) const {
  bool hurt = s.enemy_seen && s.value[int(AgentSense::EnemyDistance)] <= t.damage_range;
  a.health += (hurt ? -t.damage_per_s : t.regen_per_s) * dt;
  a.health = std::clamp(a.health, 0.0, 100.0);
  if (speed < 0.1 * t.speed)
    a.energy += t.energy_recover_per_s * dt;
  else
    a.energy -= t.energy_drain_per_s * (speed / t.speed) * dt;
  a.energy = std::clamp(a.energy, 0.0, 100.0);
}

}  // namespace zonesim::zone
