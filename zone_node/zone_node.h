#pragma once
// One zone: the entities in one rectangle of the ground plane and the tick that advances them.
// tick() reads like DESIGN.md's tick list: one call per phase, each timed into the profile.

#include <mpi.h>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/entity_id.h"
#include "common/interest_grid.h"
#include "common/scene.h"
#include "crowd/vec2.h"
#include "ledger/store.h"
#include "zone_node/cluster/byte_exchange.h"
#include "zone_node/cluster/entity_mail.h"
#include "zone_node/cluster/halo.h"
#include "zone_node/cluster/load_balancer.h"
#include "zone_node/cluster/migration.h"
#include "zone_node/entity_store.h"
#include "zone_node/players.h"
#include "zone_node/quarantine.h"
#include "zone_node/systems/neighbourhood.h"
#include "zone_node/systems/step_context.h"
#include "zone_node/tick_profile.h"
#include "zone_node/time_dilation.h"
#include "zone_node/zone_layout.h"

namespace zonesim::zone {

class GatewayLink;
class CellPublisher;
class EmitterSystem;
class RigidBodySystem;
class FlockMovement;
class FlowMovement;
class FormationMovement;
class RoadMovement;
class AntMovement;
class Transactions;
class LeaderboardService;
class WanderMovement;
struct WorldMap;
class ZoneMap;
class AgentSystem;
class InteractionSystem;
class DuelSystem;
struct DuelFigures;
class ZoneSystem;
struct StepContext;

struct ZoneOptions {
  int dds_domain = 0;
  bool dds = true;       ///< false: no DDS at all (pure MPI runs)
  int check_every = 30;  ///< ticks between conservation checks (1: every tick)
  std::string gpu = "auto";
  std::string checkpoint_dir;  ///< empty: no checkpoints
  int checkpoint_every = 0;    ///< ticks between checkpoints
  BalanceSettings balance;     ///< moving zone boundaries (every = 0: fixed)
  std::uint32_t epoch = 0;     ///< the cluster epoch every DDS sample carries
  int orphan_grace_ticks = 0;  ///< an avatar with no input this long is removed (0: never)
  /// Where players' transactions are committed (zone_node --ledger); nullopt: no ledger, and
  /// every transaction fails with that reason.
  std::optional<ledger::StoreConfig> ledger;
};

struct CheckpointImage;

/// Cumulative conservation results.
struct ConservationTally {
  std::uint64_t checks = 0;
  std::uint64_t failures = 0;
  std::uint64_t last_count = 0;
  std::uint64_t mail_failures = 0;  ///< checks at which entity messages did not balance
  std::uint64_t last_mail_posted = 0;  ///< messages posted over the cluster, at the last check
};

class ZoneNode {
 public:
  /// A zone at tick 0 with the scene's initial entities, or, given a checkpoint image, at its
  /// tick with the entities it holds that fall in this rank's zone.
  ZoneNode(const Scene& scene, MPI_Comm comm, const ZoneOptions& options,
           const CheckpointImage* restart = nullptr);
  ~ZoneNode();

  /// Advances the zone by one fixed dt.
  void tick();

  int rank() const { return rank_; }
  /// The cluster epoch (ZoneOptions::epoch).
  std::uint32_t epoch() const { return options_.epoch; }
  int size() const { return size_; }
  std::uint64_t tickCount() const { return tick_; }
  /// Wall seconds per tick when running in real time (1 / tick rate).
  double tickSeconds() const { return 1.0 / scene_.tick_rate; }
  const ZoneLayout& layout() const { return layout_; }
  const EntityStore& store() const { return store_; }
  const TickProfile& profile() const { return profile_; }
  const TickCounters& counters() const { return counters_; }
  /// The players' transaction channels (zone_node/transactions.h).
  const Transactions& transactions() const { return *transactions_; }
  /// Leaderboard queries answered.
  std::uint64_t leaderboardsAnswered() const;
  /// Read-only copies of the neighbours' entities within the halo (refreshed every tick).
  const GhostStore& ghosts() const { return halo_.ghosts(); }
  const ConservationTally& conservation() const { return conservation_; }
  /// The cluster's clock rate (the same on every rank): the next tick's wall period is
  /// tickSeconds() / factor(); the scene's time_dilation key turns it on.
  const TimeDilation& dilation() const { return dilation_; }
  /// The factor the tick just run ran at (dilation() may already hold the next one's).
  double lastTickFactor() const { return last_tick_factor_; }
  /// Handoffs completed this tick: ticks from the avatar's arrival at this zone (the tick it
  /// crossed the border) to the first input applied here.
  const std::vector<CompletedHandoff>& handoffsCompleted() const {
    return players_.handoffsCompleted();
  }
  /// Entities this tick's exchange brought here (with the rank they came from).
  const std::vector<Arrival>& arrivedThisTick() const { return last_migration_.arrived; }
  /// The tick of the newest complete checkpoint (or of the one the zone restarted from).
  std::uint64_t lastCheckpointTick() const { return last_checkpoint_tick_; }
  /// Movers held frozen because their state became non-finite.
  const Quarantine& quarantine() const { return quarantine_; }
  /// Entities this tick's exchange moved to other ranks (with their destination).
  const std::vector<Departure>& migratedThisTick() const { return last_migration_.departed; }
  /// Taken items that left the world this tick (their decision checkpointed).
  const std::vector<EntityId>& itemsLeftThisTick() const { return items_left_; }
  /// Position and velocity of every live particle of this zone's emitters.
  std::vector<std::array<double, 6>> liveParticles() const;
  /// Which backend the particle emitters use ("cpu", "opencl" or "none").
  std::string particleBackend() const;
  /// The scene's obstacle map (`map:` key), or null when it has none.
  const WorldMap* worldMap() const;
  /// Which backend the flocking populations use ("cpu", "opencl" or "none").
  std::string flockBackend() const;
  /// Ids of the flow-field NPCs of this zone that reached their destination this tick.
  const std::vector<std::uint64_t>& flowArrivalsThisTick() const;
  /// The duels against adaptive NPCs this zone runs (scene key `adaptation`), in scene order.
  std::vector<DuelFigures> duelFigures() const;

 private:
  /// Runs one phase, timing it into the profile.
  void timed(Phase phase, void (ZoneNode::*run)());
  void input();
  void ai();
  void avatars();
  void physics();
  void gpu();
  void migrate();
  /// Delivers this tick's entity messages (after the exchange: targets are where they stay).
  void deliverMail();
  /// Removes the items granted to a claimant once a checkpoint holds the decision (at once
  /// without checkpoints): what clients see go never comes back after a restart.
  void removeTakenItems();
  void halo();
  void publish();
  void checks();
  void checkConservationNow();
  /// With time dilation on: one allreduce of this tick's work sets the next tick's factor.
  void dilate();
  /// Readies the cell writers of this zone's rectangle (at start and when boundaries move).
  void coverZone();

  /// What the player protocol changes in this zone this tick.
  PlayerZone playerZone();
  /// What the systems read and write this tick.
  StepContext stepContext();

  const Scene& scene_;
  MPI_Comm comm_;
  int rank_, size_;
  ZoneOptions options_;
  ZoneLayout layout_;
  InterestGrid grid_;
  EntityStore store_;
  EntityIdAllocator ids_;
  IdSetDigest ledger_;  // created here minus destroyed here
  Migrator migrator_;
  LoadBalancer balancer_;
  HaloExchange halo_;
  EntityMail mail_;  // messages between entities, delivered in the migrate phase
  bool halo_needed_ = false;      // some system reads ghosts (decided from the scene: all agree)
  bool bodies_in_scene_ = false;  // rigid bodies may touch across borders
  double walker_reach_ = 0;       // widest radius at which walkers see each other
  Neighbourhood near_;            // walkers and their ghosts, rebuilt each AI phase
  Quarantine quarantine_;         // movers whose state became non-finite, held frozen
  std::uint64_t layout_version_ = 0;  // bumped whenever zone boundaries move
  std::unique_ptr<GatewayLink> link_;
  std::unique_ptr<CellPublisher> publisher_;
  std::unique_ptr<EmitterSystem> emitters_;
  std::unique_ptr<RigidBodySystem> bodies_;  // created when the first body shows up
  std::unique_ptr<FlockMovement> flocks_;    // flocking NPC populations of the scene
  std::unique_ptr<ZoneMap> map_;  // the scene's walls as the doors leave them; null without `map:`
  std::unique_ptr<FlowMovement> flows_;            // flow-field NPC populations (need map_)
  std::unique_ptr<FormationMovement> formations_;  // fixed groups (need map_)
  std::unique_ptr<RoadMovement> roads_;            // road networks (waypoint graphs)
  std::unique_ptr<AntMovement> ants_;              // ant colonies (need map_)
  std::unique_ptr<AgentSystem> agents_;            // AI agents (scene key `agents`)
  std::unique_ptr<WanderMovement> wanderers_;      // NPCs between random waypoints
  std::unique_ptr<InteractionSystem> interactions_;  // hits and gifts (scene key `interactions`)
  std::unique_ptr<DuelSystem> duels_;  // duels against adaptive NPCs (scene key `adaptation`)
  /// The AI phase's systems in the order they step, each with its stage of the profile.
  std::vector<std::pair<Stage, ZoneSystem*>> ai_systems_;
  ByteExchange system_bytes_;             // the systems' byte swaps (Collectives::swap)
  Collectives collectives_;               // what the systems may ask of the whole cluster
  std::vector<crowd::Vec2> lod_players_;  // every avatar of the cluster, for crowd LOD
  Players players_;                       // the player protocol
  std::unique_ptr<Transactions> transactions_;  // players' reliable transaction channels
  std::unique_ptr<LeaderboardService> leaderboard_;  // answers players' leaderboard queries

  std::uint64_t tick_ = 0;
  std::uint64_t last_checkpoint_tick_ = 0;  // the newest complete checkpoint's (or the restored)
  std::uint64_t link_failures_seen_ = 0;
  std::map<std::uint32_t, std::uint64_t> inherited_counters_;  // id counters a restart read
  TickProfile profile_;
  TickCounters counters_;
  ConservationTally conservation_;
  TimeDilation dilation_;
  double last_tick_factor_ = 1;
  double own_work_seconds_ = 0;  // CPU time of this tick's input..gpu and publish
  MigrationResult last_migration_;
  std::vector<Departure> leavers_;  // migrated away or destroyed this tick: publish says so
  std::vector<EntityId> items_left_;  // taken items removed this tick
};

}  // namespace zonesim::zone
