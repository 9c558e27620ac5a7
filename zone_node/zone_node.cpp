#include "zone_node/zone_node.h"

#include <stdexcept>

#include "common/log.h"
#include "zone_node/cluster/checkpoint.h"
#include "zone_node/cluster/conservation.h"
#include "zone_node/cluster/offload_agreement.h"
#include "zone_node/cluster/player_positions.h"
#include "zone_node/cluster/trail_exchange.h"
#include "zone_node/cluster/value_gather.h"
#include "zone_node/leaderboard_service.h"
#include "zone_node/net/cell_publisher.h"
#include "zone_node/net/gateway_link.h"
#include "zone_node/population.h"
#include "zone_node/systems/agent_system.h"
#include "zone_node/systems/ant_movement.h"
#include "zone_node/systems/avatar_movement.h"
#include "zone_node/systems/duels.h"
#include "zone_node/systems/emitters.h"
#include "zone_node/systems/flock_movement.h"
#include "zone_node/systems/flow_movement.h"
#include "zone_node/systems/formation_movement.h"
#include "zone_node/systems/interactions.h"
#include "zone_node/systems/npc_movement.h"
#include "zone_node/systems/offload_probe.h"
#include "zone_node/systems/rigid_bodies.h"
#include "zone_node/systems/road_movement.h"
#include "zone_node/systems/step_context.h"
#include "zone_node/transactions.h"
#include "zone_node/world_map.h"
#include "zone_node/zone_map.h"

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
      halo_(comm, rank_, size_, scene.halo_width, haloSkin(scene)),
      mail_(comm, rank_, size_),
      system_bytes_(comm, size_),
      players_(scene, rank_, size_, options.orphan_grace_ticks),
      dilation_(scene.time_dilation, scene.tick_rate) {
  for (const NpcPopulation& p : scene.npcs)
    walker_reach_ = std::max(walker_reach_, p.separation_radius);
  for (const RigidBodyPopulation& p : scene.rigid_bodies) bodies_in_scene_ |= p.count > 0;
  bodies_in_scene_ |= !scene.physics.bodies.empty();
  // Thresholds timed on rank 0 only and shared (collective), so that every rank puts particles
  // and flocks on the same backend. --gpu probe times both workloads; auto times the flocks
  // (no default fits them: their crossover moved from 2,000 to 7,400 agents with the load)
  // when one is large enough that the device could win, and keeps the particles' measured
  // default (a scene's sprays would otherwise switch between float and double with the load).
  const bool probe = options_.gpu == "probe";
  const ProbedWorkloads probed = probedWorkloads(scene_, options_.gpu);
  const std::string gpu_mode = probe ? "auto" : options_.gpu;
  const gpu::OffloadThresholds thresholds = agreedThresholds(
      comm_, probed.any(), [probed](gpu::OffloadThresholds& t) { probeZoneThresholds(t, probed); });
  flocks_ = std::make_unique<FlockMovement>(scene, gpu_mode, thresholds, size_);
  map_ = ZoneMap::load(scene);
  const WorldMap* walls = map_ ? &map_->world() : nullptr;
  flows_ = std::make_unique<FlowMovement>(scene, map_.get());
  formations_ = std::make_unique<FormationMovement>(scene, walls);
  roads_ = std::make_unique<RoadMovement>(scene.npcs);
  ants_ = std::make_unique<AntMovement>(scene, walls);
  agents_ = std::make_unique<AgentSystem>(scene, map_.get());
  wanderers_ = std::make_unique<WanderMovement>(scene);
  interactions_ = std::make_unique<InteractionSystem>(scene.interactions, scene.dt, mail_, rank_);
  duels_ = std::make_unique<DuelSystem>(scene.adaptation, scene.seed, [this](double x, double z) {
    return layout_.ownerOf(x, z) == rank_;
  });
  // The path budget is the cluster's: zones share their oldest requests' keys every tick. The
  // ants' trail deposits are summed in integers, the same on every rank.
  if (size_ > 1)
    collectives_.gather = [this](const std::vector<std::uint64_t>& v) {
      return gatherValues(comm_, v);
    };
  collectives_.sum = [this](std::span<std::int64_t> v) { sumTrailDeltas(comm_, v); };
  if (size_ > 1)
    collectives_.swap = [this](const std::vector<std::vector<std::uint8_t>>& out) {
      return system_bytes_.swap(out);
    };
  collectives_.rank = rank_;
  collectives_.ranks = size_;
  // Hits, gifts and agents first: they read everyone where the tick found them, as their
  // ghosts are.
  ai_systems_ = {{Stage::AiInteractions, interactions_.get()},
                 {Stage::AiAgents, agents_.get()},
                 {Stage::AiWander, wanderers_.get()},
                 {Stage::AiFlock, flocks_.get()},
                 {Stage::AiFlow, flows_.get()},
                 {Stage::AiFormations, formations_.get()},
                 {Stage::AiRoads, roads_.get()},
                 {Stage::AiAnts, ants_.get()},
                 {Stage::AiAdaptation, duels_.get()}};
  // Flocks and flow crowds read their neighbours across borders as ghosts too, and agents see
  // enemies there.
  halo_needed_ = walker_reach_ > 0 || bodies_in_scene_ || flocks_->active() || flows_->active() ||
                 formations_->active() || (agents_->active() && agents_->reach() > 0) ||
                 interactions_->active();

  auto keepIfMine = [&](const EntityRecordData& r) {
    if (layout_.ownerOf(r.pos.x(), r.pos.z()) != rank_) return;
    store_.add(r);
    ledger_.add(r.id);
  };
  if (restart) {
    tick_ = restart->tick;
    last_checkpoint_tick_ = restart->tick;
    inherited_counters_ = restart->id_counters;
    auto counter = restart->id_counters.find(std::uint32_t(rank_));
    if (counter != restart->id_counters.end())
      ids_ = EntityIdAllocator(std::uint32_t(rank_), counter->second);
    for (const EntityRecordData& r : restart->entities) keepIfMine(r);
  } else {
    forEachInitialEntity(scene_, keepIfMine);
  }
  if (options_.dds) {
    link_ = std::make_unique<GatewayLink>(options_.dds_domain, rank_, options_.epoch);
    publisher_ = std::make_unique<CellPublisher>(link_->participant(), link_->topics(), grid_,
                                                 rank_, scene_, options_.epoch);
    coverZone();
  }
  std::unique_ptr<ledger::LedgerCommitter> committer;
  if (options_.ledger)
    committer = std::make_unique<ledger::LedgerCommitter>(ledger::openStore(*options_.ledger));
  transactions_ = std::make_unique<Transactions>(std::move(committer));
  // The leaderboard on a connection of its own: its reads never wait behind a commit batch.
  leaderboard_ = std::make_unique<LeaderboardService>(
      options_.ledger ? std::make_unique<ledger::LeaderboardCache>(
                            ledger::openStore(*options_.ledger), dds::kLeaderboardRows)
                      : nullptr);
  PlayerZone zone = playerZone();
  players_.restored(zone);
  emitters_ = std::make_unique<EmitterSystem>(scene_.emitters, gpu_mode, thresholds);
  // What the active systems read on ghosts (the scene decides: every rank registers alike).
  for (auto [stage, system] : ai_systems_)
    if (system->active())
      for (GhostColumn& c : system->ghostColumns()) halo_.addColumn(std::move(c));
  // The first tick's systems already read ghosts.
  halo();
}

ZoneNode::~ZoneNode() = default;

std::uint64_t ZoneNode::leaderboardsAnswered() const {
  return leaderboard_->answered();
}

std::vector<std::array<double, 6>> ZoneNode::liveParticles() const {
  std::vector<std::array<double, 6>> out;
  emitters_->liveParticles(out);
  return out;
}

std::string ZoneNode::particleBackend() const {
  return emitters_->backendName();
}

const WorldMap* ZoneNode::worldMap() const {
  return map_ ? &map_->world() : nullptr;
}

std::string ZoneNode::flockBackend() const {
  return flocks_->backendName();
}

const std::vector<std::uint64_t>& ZoneNode::flowArrivalsThisTick() const {
  return flows_->arrivedLastStep();
}

std::vector<DuelFigures> ZoneNode::duelFigures() const {
  return duels_->figures();
}

void ZoneNode::tick() {
  profile_ = {};
  counters_ = {};
  leavers_.clear();
  items_left_.clear();
  players_.startTick();
  last_tick_factor_ = dilation_.factor();
  std::int64_t cpu0 = threadCpuNs();
  timed(Phase::Input, &ZoneNode::input);
  timed(Phase::Ai, &ZoneNode::ai);
  timed(Phase::Avatars, &ZoneNode::avatars);
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
  own_work_seconds_ = double((cpu1 - cpu0) + (cpu3 - cpu2)) * 1e-9;
  balancer_.record(own_work_seconds_);
  timed(Phase::Checks, &ZoneNode::checks);
}

void ZoneNode::timed(Phase phase, void (ZoneNode::*run)()) {
  ScopedTimer t(profile_[phase]);
  (this->*run)();
}

PlayerZone ZoneNode::playerZone() {
  return {store_, ledger_, ids_, leavers_, counters_, link_.get(), tick_};
}

StepContext ZoneNode::stepContext() {
  collectives_.zone = layout_.rect(rank_);
  return {store_,       &halo_.ghosts(), near_,    scene_.dt, tick_, double(tick_) * scene_.dt,
          lod_players_, collectives_,    counters_};
}

void ZoneNode::input() {
  PlayerZone zone = playerZone();
  players_.input(zone);
  // After the spawns: a player's first transaction may come with its avatar.
  transactions_->input(zone);
}

void ZoneNode::ai() {
  quarantine_.begin(store_);
  // The doors change the one map every system reads, before any of them steps.
  if (map_ && map_->hasDoors()) {
    ScopedTimer t(profile_[Stage::AiDoors]);
    map_->applyDoors(double(tick_) * scene_.dt);
  }
  if (walker_reach_ > 0) {
    ScopedTimer t(profile_[Stage::AiNeighbours]);
    // A flyer higher above the ground than any walker reaches is nobody's neighbour.
    near_.build(store_, &halo_.ghosts(), walker_reach_, scene_.world.min.y + walker_reach_);
  }
  // Every rank takes part in the gather (the scene decides, so all agree).
  if (scene_.lod.enabled && (flocks_->active() || flows_->active() || agents_->active())) {
    ScopedTimer t(profile_[Stage::AiLod]);
    lod_players_ = lodPlayers(comm_, store_, scene_.lod);
  }
  StepContext ctx = stepContext();
  for (auto [stage, system] : ai_systems_) {
    if (!system->active()) continue;
    ScopedTimer t(profile_[stage]);
    system->step(ctx);
  }
}

void ZoneNode::avatars() {
  stepAvatars(scene_.world, store_, scene_.dt);
  // Before physics, the halo, migration and publish read what the movers wrote.
  counters_.quarantined = quarantine_.apply(store_);
}

void ZoneNode::physics() {
  // On several ranks every zone takes part in each tick's island exchange (collective), with
  // bodies or not; on one, the system starts with the first body or cloth.
  const bool cluster_bodies = bodies_in_scene_ && size_ > 1;
  if ((cluster_bodies || store_.count(EntityKind::RigidBody) > 0 ||
       !scene_.physics.cloths.empty()) &&
      !bodies_)
    bodies_ = std::make_unique<RigidBodySystem>(scene_, rank_);
  if (!bodies_) return;
  const std::uint64_t frozen_before = bodies_->quarantined();
  StepContext ctx = stepContext();
  bodies_->step(ctx);
  counters_.quarantined += bodies_->quarantined() - frozen_before;
  const physics::StepProfile& p = bodies_->profile();
  profile_[Stage::PhysicsIntegrate] += p.integrate;
  profile_[Stage::PhysicsBroadphase] += p.broadphase;
  profile_[Stage::PhysicsNarrowphase] += p.narrowphase;
  profile_[Stage::PhysicsPrepare] += p.prepare;
  profile_[Stage::PhysicsSolve] += p.solve;
  profile_[Stage::PhysicsIslands] += p.islands;
  profile_[Stage::PhysicsBorder] += bodies_->borderTime();
}

void ZoneNode::gpu() {
  StepContext ctx = stepContext();
  emitters_->step(ctx);
}

void ZoneNode::migrate() {
  last_migration_ = migrator_.exchange(store_, layout_, tick_, players_.forwardQueues());
  counters_.migrated_out = last_migration_.departed.size();
  counters_.migrated_in = last_migration_.arrived.size();
  counters_.migration_bytes = last_migration_.bytes_sent;
  PlayerZone zone = playerZone();
  players_.migrated(zone, last_migration_);
  leavers_.insert(leavers_.end(), last_migration_.departed.begin(), last_migration_.departed.end());
  deliverMail();
}

void ZoneNode::deliverMail() {
  if (!interactions_->active()) return;  // the scene decides: every rank skips alike
  ScopedTimer t(profile_[Stage::MigrateMail]);
  auto receive = [this](EntityStore& store, std::span<const EntityMessage> arrived,
                        std::vector<EntityMessage>& replies) {
    interactions_->receive(store, arrived, replies, counters_);
  };
  auto refused = [this](const EntityMessage& m, MailRefusal, std::vector<EntityMessage>& replies) {
    interactions_->refused(m, replies, counters_);
  };
  MailStats s = mail_.deliver(store_, last_migration_.departed, receive, refused);
  removeTakenItems();
  counters_.mail_posted = s.posted;
  counters_.mail_applied = s.applied;
  counters_.mail_cross_zone = s.cross_zone;
  counters_.mail_forwarded = s.forwarded;
  counters_.mail_refused = s.refused;
  counters_.mail_bytes = s.bytes_sent;
}

void ZoneNode::removeTakenItems() {
  if (store_.count(EntityKind::Item) == 0) return;
  // Without checkpoints nothing is ever rolled back: a decision is final at once.
  const bool checkpointing = options_.checkpoint_every > 0 && !options_.checkpoint_dir.empty();
  for (std::size_t i = store_.size(); i-- > 0;) {
    const std::uint64_t taken_at = store_.combat[i].taken_at;
    if (store_.kind[i] != EntityKind::Item || taken_at == 0) continue;
    if (checkpointing && last_checkpoint_tick_ < taken_at) continue;
    leavers_.push_back({store_.id[i], EntityKind::Item, -1, store_.dr[i].cell, 0, false});
    items_left_.push_back(store_.id[i]);
    ledger_.remove(store_.id[i]);
    store_.removeAt(i);
    ++counters_.items_removed;
  }
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
  PlayerZone zone = playerZone();
  transactions_->publish(zone);
  leaderboard_->serve(*link_);
  publisher_->setDilation(dilation_.factor());
  PublishStats s = publisher_->publish(store_, leavers_, tick_, double(tick_) * scene_.dt);
  counters_.published_updates = s.updates;
  counters_.published_enters = s.enters;
  counters_.published_leaves = s.leaves;
  counters_.published_cells = s.cells_written;
  counters_.published_keyframes = s.keyframes;
  counters_.subscribed_cells = s.subscribed_cells;
  counters_.published_states = s.states_computed;
  counters_.published_histories = s.histories_kept;
  counters_.dds_write_failures = s.write_failures + link_->writeFailures() - link_failures_seen_;
  link_failures_seen_ = link_->writeFailures();
}

void ZoneNode::checks() {
  if (options_.checkpoint_every > 0 && !options_.checkpoint_dir.empty() &&
      tick_ % std::uint64_t(options_.checkpoint_every) == 0) {
    writeCheckpoint(comm_, store_, tick_, ids_.issued(), inherited_counters_,
                    options_.checkpoint_dir);
    last_checkpoint_tick_ = tick_;  // written by every rank and named LATEST (collective)
  }
  if (options_.check_every > 0 && tick_ % std::uint64_t(options_.check_every) == 0)
    checkConservationNow();
  // Moved boundaries take effect in the next migrate phase: leavers go to their new owners.
  if (balancer_.check(tick_, layout_)) {
    ++counters_.rebalances;
    ++layout_version_;
    coverZone();
  }
  counters_.imbalance_permille = std::uint64_t(balancer_.imbalance() * 1000.0);
  dilate();
}

void ZoneNode::dilate() {
  if (!scene_.time_dilation.enabled) return;
  // The rank's own work in CPU time, as the balancer reads it: waits on other ranks would
  // count the slowest rank's work again on every rank, and time a loaded machine took the
  // CPU away would dilate the clock for a load that is not the simulation's (and slowing the
  // clock does not give the CPU back).
  double slowest = 0;
  MPI_Allreduce(&own_work_seconds_, &slowest, 1, MPI_DOUBLE, MPI_MAX, comm_);
  if (dilation_.record(slowest, tick_) && rank_ == 0)
    ZS_INFO("time dilation %.0f%% from tick %llu", dilation_.factor() * 100.0,
            (unsigned long long)tick_);
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
  if (!interactions_->active()) return;
  MailBalance mail = sumMailAudit(comm_, mail_.audit());
  conservation_.last_mail_posted = mail.posted.count;
  if (!mail.ok()) {
    ++conservation_.mail_failures;
    ZS_ERROR("entity messages unbalanced at tick %llu: %llu posted, %llu applied or refused",
             (unsigned long long)tick_, (unsigned long long)mail.posted.count,
             (unsigned long long)mail.settled.count);
  }
}

}  // namespace zonesim::zone
