#include "zone_node/zone_node.h"

#include <stdexcept>

#include "common/log.h"
#include "zone_node/cluster/checkpoint.h"
#include "zone_node/cluster/conservation.h"
#include "zone_node/cluster/offload_agreement.h"
#include "zone_node/cluster/player_positions.h"
#include "zone_node/cluster/trail_exchange.h"
#include "zone_node/cluster/value_gather.h"
#include "zone_node/net/cell_publisher.h"
#include "zone_node/net/zone_link.h"
#include "zone_node/population.h"
#include "zone_node/systems/agent_system.h"
#include "zone_node/systems/ant_movement.h"
#include "zone_node/systems/avatar_movement.h"
#include "zone_node/systems/emitters.h"
#include "zone_node/systems/flock_movement.h"
#include "zone_node/systems/flow_movement.h"
#include "zone_node/systems/formation_movement.h"
#include "zone_node/systems/npc_movement.h"
#include "zone_node/systems/rigid_bodies.h"
#include "zone_node/systems/road_movement.h"
#include "zone_node/world_map.h"

namespace zonesim::zone {

namespace {
int rankIn(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}
int sizeOf(MPI_Comm comm) {
  int s = 1;
  MPI_Comm_size(comm, &s);
  return s;
}
}  // namespace

ZoneNode::ZoneNode(const Scene& scene, MPI_Comm comm, const ZoneOptions& options,
                   const CheckpointImage* restart)
    : scene_(scene),
      comm_(comm),
      rank_(rankIn(comm)),
      size_(sizeOf(comm)),
      options_(options),
      layout_(ZoneLayout::forRanks(scene, size_)),
      grid_(scene.world, scene.interest_cell_size),
      ids_(std::uint32_t(rank_)),
      migrator_(comm, rank_, size_),
      balancer_(comm, options.balance),
      // The skin lets send lists live for several ticks of motion (LAMMPS' neighbour skin).
      halo_(comm, rank_, size_, scene.halo_width, std::max(1.0, 0.2 * scene.halo_width)) {
  // Jointed bodies do not migrate together and a cloth belongs to no entity: one zone only
  // (the loader checks the scene's zones; this catches a run on more ranks).
  if (size_ > 1 && (!scene.physics.joints.empty() || !scene.physics.cloths.empty())) {
    throw std::runtime_error(scene.name +
                             ": physics.joints and physics.cloths need a single zone;"
                             " run on 1 rank, not " +
                             std::to_string(size_));
  }
  for (const NpcPopulation& p : scene.npcs)
    walker_reach_ = std::max(walker_reach_, p.separation_radius);
  for (const RigidBodyPopulation& p : scene.rigid_bodies) bodies_in_scene_ |= p.count > 0;
  bodies_in_scene_ |= !scene.physics.bodies.empty();
  // --gpu probe: auto, with thresholds timed on rank 0 only and shared (collective), so that
  // every rank puts particles and flocks on the same backend.
  bool offloadable = false;
  for (const EmitterPopulation& p : scene_.emitters) offloadable |= p.count > 0;
  for (const NpcPopulation& p : scene_.npcs) offloadable |= p.flock.enabled && p.count > 0;
  const bool probe = options_.gpu == "probe";
  const std::string gpu_mode = probe ? "auto" : options_.gpu;
  const gpu::OffloadThresholds thresholds = agreedThresholds(comm_, probe && offloadable);
  flocks_ = std::make_unique<FlockMovement>(scene, gpu_mode, thresholds, size_);
  map_ = loadWorldMap(scene);
  flows_ = std::make_unique<FlowMovement>(scene, map_.get());
  formations_ = std::make_unique<FormationMovement>(scene, map_.get());
  roads_ = std::make_unique<RoadMovement>(scene);
  ants_ = std::make_unique<AntMovement>(scene, map_.get());
  agents_ = std::make_unique<AgentSystem>(scene, map_ ? &map_->grid : nullptr,
                                          map_ ? map_->frame : crowd::MapFrame{});
  // The path budget is the cluster's: zones share their oldest requests' keys every tick.
  if (size_ > 1)
    agents_->setGather(
        [this](const std::vector<std::uint64_t>& v) { return gatherValues(comm_, v); });
  // Flocks and flow crowds read their neighbours across borders as ghosts too, and agents see
  // enemies there.
  halo_needed_ = walker_reach_ > 0 || bodies_in_scene_ || flocks_->active() || flows_->active() ||
                 formations_->active() || (agents_->active() && agents_->reach() > 0);
  forward_.resize(std::size_t(size_));

  auto keepIfMine = [&](const EntityRecordData& r) {
    if (layout_.ownerOf(r.pos.x(), r.pos.z()) != rank_) return;
    store_.add(r);
    ledger_.add(r.id);
    if (r.kind == EntityKind::Avatar) known_players_.insert(r.avatar.player_id);
  };
  if (restart) {
    tick_ = restart->tick;
    inherited_counters_ = restart->id_counters;
    auto counter = restart->id_counters.find(std::uint32_t(rank_));
    if (counter != restart->id_counters.end())
      ids_ = EntityIdAllocator(std::uint32_t(rank_), counter->second);
    for (const EntityRecordData& r : restart->entities) keepIfMine(r);
  } else {
    forEachInitialEntity(scene_, keepIfMine);
  }
  if (options_.dds) {
    link_ = std::make_unique<ZoneLink>(options_.dds_domain, rank_);
    publisher_ = std::make_unique<CellPublisher>(link_->participant(), link_->topics(), grid_,
                                                 rank_, scene_);
    coverZone();
    // After a restart the gateways must learn where the restored avatars live now.
    for (std::size_t i = 0; i < store_.size(); ++i)
      if (store_.kind[i] == EntityKind::Avatar)
        link_->announce({store_.avatar[i].player_id, store_.id[i].value, -1, rank_, tick_,
                         store_.avatar[i].last_input_seq});
  }
  emitters_ = std::make_unique<EmitterSystem>(scene_, gpu_mode, thresholds);
  // The first tick's systems already read ghosts.
  halo();
}

ZoneNode::~ZoneNode() = default;

std::vector<std::array<double, 6>> ZoneNode::liveParticles() const {
  std::vector<std::array<double, 6>> out;
  emitters_->liveParticles(out);
  return out;
}

std::string ZoneNode::particleBackend() const {
  return emitters_->backendName();
}

std::string ZoneNode::flockBackend() const {
  return flocks_->backendName();
}

void ZoneNode::tick() {
  profile_ = {};
  counters_ = {};
  leavers_.clear();
  handoff_latency_ticks_.clear();
  std::int64_t cpu0 = threadCpuNs();
  timed(Phase::Input, &ZoneNode::input);
  timed(Phase::Ai, &ZoneNode::ai);
  timed(Phase::Physics, &ZoneNode::physics);
  timed(Phase::Gpu, &ZoneNode::gpu);
  std::int64_t cpu1 = threadCpuNs();
  timed(Phase::Migrate, &ZoneNode::migrate);
  timed(Phase::Halo, &ZoneNode::halo);
  std::int64_t cpu2 = threadCpuNs();
  timed(Phase::Publish, &ZoneNode::publish);
  std::int64_t cpu3 = threadCpuNs();
  ++tick_;
  // The rank's own work, in CPU time: migrate and checks wait on other ranks, and wall time
  // also grows while a rank is descheduled; either would hide or fake an imbalance.
  balancer_.record(double((cpu1 - cpu0) + (cpu3 - cpu2)) * 1e-9);
  timed(Phase::Checks, &ZoneNode::checks);
}

void ZoneNode::timed(Phase phase, void (ZoneNode::*run)()) {
  ScopedTimer t(profile_[phase]);
  (this->*run)();
}

void ZoneNode::input() {
  for (const ForwardedInput& f : forwarded_in_) applyInput(f.player_id, f.seq, f.move_x, f.move_z);
  forwarded_in_.clear();
  if (link_) {
    for (const SpawnRequestMsg& s : link_->takeSpawnRequests()) spawnAvatar(s.player_id, s.x, s.z);
    for (std::uint64_t player : link_->takeDespawnRequests()) despawnAvatar(player);
    for (const PlayerInputMsg& in : link_->takeInputs())
      applyInput(in.player_id, in.seq, in.move_x, in.move_z);
  }
  releaseHeldInputs();
}

void ZoneNode::spawnAvatar(std::uint64_t player_id, double x, double z) {
  // Every zone reads every request, so all agree on which players exist; repeats are ignored,
  // and so is a request whose player already left (the despawn overtook it).
  bool seen = !known_players_.insert(player_id).second;
  if (despawned_players_.count(player_id)) return;
  std::optional<std::size_t> mine = store_.avatarOf(player_id);
  if (seen) {
    if (mine && link_) {
      link_->announce({player_id, store_.id[*mine].value, -1, rank_, tick_,
                       store_.avatar[*mine].last_input_seq});
    }
    return;
  }
  // The creator is chosen without the layout: zones read the request in different ticks, and
  // boundaries may move in between. Migration then takes the avatar to its owner, which
  // announces it (see migrate()).
  if (player_id % std::uint64_t(size_) != std::uint64_t(rank_)) return;
  x = std::clamp(x, scene_.world.min.x, scene_.world.max.x - 1e-6);
  z = std::clamp(z, scene_.world.min.z, scene_.world.max.z - 1e-6);
  EntityRecordData r;
  r.id = ids_.next();
  r.kind = EntityKind::Avatar;
  r.pos = Vec3(x, scene_.world.min.y, z);
  r.avatar.player_id = player_id;
  r.avatar.max_speed = scene_.clients.speed;
  store_.add(r);
  ledger_.add(r.id);
  ++counters_.avatars_spawned;
  unannounced_.push_back(r.id);
  ZS_DEBUG("spawned avatar %s for player %llu", toString(r.id).c_str(),
           (unsigned long long)player_id);
}

void ZoneNode::despawnAvatar(std::uint64_t player_id) {
  // Every zone remembers the request: an avatar migrating while zones read it is removed on
  // arrival at a zone that has already seen it.
  despawned_players_.insert(player_id);
  departed_players_.erase(player_id);
  if (std::optional<std::size_t> i = store_.avatarOf(player_id)) destroyAt(*i);
}

void ZoneNode::destroyAt(std::size_t index) {
  leavers_.push_back({store_.id[index], store_.kind[index], -1, store_.dr[index].cell,
                      store_.avatar[index].player_id, false});
  ledger_.remove(store_.id[index]);
  store_.removeAt(index);
  ++counters_.entities_destroyed;
}

void ZoneNode::applyInput(std::uint64_t player_id, std::uint32_t seq, float move_x, float move_z) {
  if (std::optional<std::size_t> i = store_.avatarOf(player_id)) {
    AvatarData& a = store_.avatar[*i];
    if (seq <= a.last_input_seq) {
      ++counters_.inputs_duplicate;  // already applied (e.g. forwarded copy): exactly once
      return;
    }
    // Ahead of a missing number (typically the forwarded input the old owner still holds after
    // a handoff): held until the gap fills or kInputHoldTicks pass, so inputs apply in order.
    if (a.last_input_seq != 0 && seq > a.last_input_seq + 1) {
      if (held_inputs_[player_id].try_emplace(seq, HeldInput{move_x, move_z, tick_}).second)
        ++counters_.inputs_held;
      return;
    }
    a.last_input_seq = seq;
    a.move_x = move_x;
    a.move_z = move_z;
    ++counters_.inputs_applied;
    auto started = handoff_started_.find(player_id);
    if (started != handoff_started_.end()) {
      handoff_latency_ticks_.push_back(tick_ - started->second);
      handoff_started_.erase(started);
    }
    return;
  }
  auto gone = departed_players_.find(player_id);
  if (gone != departed_players_.end()) {
    forward_[std::size_t(gone->second)].push_back({player_id, 0, seq, move_x, move_z});
    ++counters_.inputs_forwarded;
    return;
  }
  ++counters_.inputs_unroutable;
}

void ZoneNode::releaseHeldInputs() {
  for (auto player = held_inputs_.begin(); player != held_inputs_.end();) {
    std::map<std::uint32_t, HeldInput>& held = player->second;
    std::optional<std::size_t> i = store_.avatarOf(player->first);
    while (!held.empty()) {
      auto [seq, in] = *held.begin();
      if (i) {
        AvatarData& a = store_.avatar[*i];
        if (seq > a.last_input_seq + 1) {
          if (tick_ - in.since_tick < kInputHoldTicks) break;      // the gap may still fill
          counters_.inputs_skipped += seq - a.last_input_seq - 1;  // it did not: never arrived
          a.last_input_seq = seq - 1;
        }
      }
      held.erase(held.begin());
      applyInput(player->first, seq, in.move_x, in.move_z);  // here, or forwarded if it left
    }
    player = held.empty() ? held_inputs_.erase(player) : std::next(player);
  }
}

void ZoneNode::ai() {
  if (walker_reach_ > 0) near_.build(store_, &halo_.ghosts(), walker_reach_);
  // Agents first: they sense the walkers where the tick found them, as their ghosts are.
  if (agents_->active()) {
    AgentTickStats a = agents_->step(store_, &halo_.ghosts(), double(tick_) * scene_.dt, scene_.dt);
    counters_.agents = a.agents;
    counters_.agent_transitions = a.transitions;
    counters_.paths_planned = a.paths.planned;
    counters_.paths_queued = a.paths.queued;
    counters_.path_replans = a.paths.replans;
  }
  stepNpcs(scene_, store_, near_, double(tick_) * scene_.dt, scene_.dt);
  // Every rank takes part in the gather (the scene decides, so all agree).
  if (scene_.lod.enabled && (flocks_->active() || flows_->active()))
    players_ = lodPlayers(comm_, store_, scene_.lod);
  if (flocks_->active())
    flocks_->step(store_, &halo_.ghosts(), scene_.dt, players_, std::int64_t(tick_));
  if (flows_->active()) {
    flows_->applyDoors(double(tick_) * scene_.dt);
    flows_->step(store_, &halo_.ghosts(), scene_.dt, players_, std::int64_t(tick_));
  }
  if (formations_->active()) formations_->step(store_, &halo_.ghosts(), scene_.dt, tick_);
  if (roads_->active()) roads_->step(store_, scene_.dt, tick_);
  if (ants_->active()) {
    // Every rank's deposits of this tick, summed exactly on every rank (the scene decides that
    // there are colonies, so all take part), then the trails evaporate alike everywhere.
    ants_->step(store_, tick_, scene_.dt);
    sumTrailDeltas(comm_, ants_->deltas());
    ants_->applyTrails();
  }
  stepAvatars(scene_.world, store_, scene_.dt);
}

void ZoneNode::physics() {
  if ((store_.count(EntityKind::RigidBody) > 0 || !scene_.physics.cloths.empty()) && !bodies_)
    bodies_ = std::make_unique<RigidBodySystem>(scene_, rank_);
  if (bodies_) counters_.bodies_awake = bodies_->step(store_, &halo_.ghosts(), scene_.dt, tick_);
  if (!bodies_in_scene_ || size_ == 1) return;
  // Contacts across borders: the pushes this zone gave its neighbours' bodies go back to them
  // (every rank takes part, bodies or not, as the exchange is collective).
  static const std::vector<GhostImpulse> kNone;
  std::vector<GhostImpulse> in = halo_.reverse(bodies_ ? bodies_->ghostImpulses() : kNone);
  counters_.ghost_impulses_in = in.size();
  if (bodies_) bodies_->applyImpulses(store_, in);
}

void ZoneNode::gpu() {
  counters_.particles_alive = emitters_->step(store_, scene_.dt);
}

void ZoneNode::migrate() {
  last_migration_ = migrator_.exchange(store_, layout_, tick_, forward_);
  counters_.migrated_out = last_migration_.departed.size();
  counters_.migrated_in = last_migration_.arrived.size();
  counters_.migration_bytes = last_migration_.bytes_sent;
  for (const Departure& d : last_migration_.departed) {
    if (!d.announced_avatar) continue;
    departed_players_[d.player_id] = d.to_rank;
    ++counters_.handoffs_out;
  }
  std::vector<EntityId> gone_players;
  for (const Arrival& a : last_migration_.arrived) {
    if (store_.kind[a.index] != EntityKind::Avatar) continue;
    const AvatarData& av = store_.avatar[a.index];
    departed_players_.erase(av.player_id);
    if (despawned_players_.count(av.player_id)) {
      gone_players.push_back(store_.id[a.index]);
      continue;
    }
    if (!av.announced) {
      unannounced_.push_back(store_.id[a.index]);  // a new avatar on its way from its creator
      continue;
    }
    ++counters_.handoffs_in;
    handoff_started_[av.player_id] = tick_;
    if (link_)
      link_->announce(
          {av.player_id, store_.id[a.index].value, a.from_rank, rank_, tick_, av.last_input_seq});
  }
  // Removed after the loop: removal moves entities and would invalidate the arrival indices.
  for (EntityId id : gone_players) destroyAt(*store_.indexOf(id));
  // New avatars that ended this exchange here are this zone's to announce as created.
  for (EntityId id : unannounced_) {
    std::optional<std::size_t> i = store_.indexOf(id);
    if (!i) continue;  // migrated on: the owner announces it
    AvatarData& av = store_.avatar[*i];
    av.announced = true;
    if (link_) link_->announce({av.player_id, id.value, -1, rank_, tick_, av.last_input_seq});
  }
  unannounced_.clear();
  forwarded_in_ = std::move(last_migration_.inputs);
  leavers_.insert(leavers_.end(), last_migration_.departed.begin(), last_migration_.departed.end());
}

void ZoneNode::halo() {
  if (!halo_needed_) return;
  HaloStats h = halo_.refresh(store_, layout_, layout_version_);
  counters_.ghosts = h.ghosts;
  counters_.ghosts_sent = h.sent;
  counters_.halo_bytes = h.bytes_sent;
  counters_.halo_rebuilds = h.rebuilt ? 1 : 0;
}

void ZoneNode::coverZone() {
  if (!publisher_) return;
  ZoneRect r = layout_.rect(rank_);
  publisher_->cover(r.min_x, r.min_z, r.max_x, r.max_z);
}

void ZoneNode::publish() {
  if (!publisher_) return;
  PublishStats s = publisher_->publish(store_, leavers_, tick_, double(tick_) * scene_.dt);
  counters_.published_updates = s.updates;
  counters_.published_enters = s.enters;
  counters_.published_leaves = s.leaves;
  counters_.published_cells = s.cells_written;
  counters_.published_keyframes = s.keyframes;
  counters_.subscribed_cells = s.subscribed_cells;
  counters_.dds_write_failures = s.write_failures + link_->writeFailures() - link_failures_seen_;
  link_failures_seen_ = link_->writeFailures();
}

void ZoneNode::checks() {
  if (options_.checkpoint_every > 0 && !options_.checkpoint_dir.empty() &&
      tick_ % std::uint64_t(options_.checkpoint_every) == 0)
    last_checkpoint_ = writeCheckpoint(comm_, store_, tick_, ids_.issued(), inherited_counters_,
                                       options_.checkpoint_dir);
  if (options_.check_every > 0 && tick_ % std::uint64_t(options_.check_every) == 0)
    checkConservationNow();
  // Moved boundaries take effect in the next migrate phase: leavers go to their new owners.
  if (balancer_.check(tick_, layout_)) {
    ++counters_.rebalances;
    ++layout_version_;
    coverZone();
  }
  counters_.imbalance_permille = std::uint64_t(balancer_.imbalance() * 1000.0);
}

void ZoneNode::checkConservationNow() {
  ConservationReport r = checkConservation(comm_, store_, ledger_);
  ++conservation_.checks;
  conservation_.last_count = r.actual.count;
  if (!r.ok()) {
    ++conservation_.failures;
    ZS_ERROR(
        "conservation violated at tick %llu: %llu entities (hash %016llx), expected %llu (hash "
        "%016llx)",
        (unsigned long long)tick_, (unsigned long long)r.actual.count,
        (unsigned long long)r.actual.hash, (unsigned long long)r.expected.count,
        (unsigned long long)r.expected.hash);
  }
}

}  // namespace zonesim::zone
