// Messages between entities on 4 real ranks (run under mpirun), through the whole tick path:
// the halo shows the targets across borders, the interaction system posts hits and gifts, the
// movers carry some entities across a border, the migration exchange moves them, and the mail
// delivers. Every kind must be applied exactly once across handoff: a hit whose target
// migrates in the same tick, a kill confirmed to a hitter that migrated, a gift to a migrating
// avatar, and gifts whose recipient is gone (returned to the giver, wherever it went). And a
// contested pickup (two claimants of one item across a border in one tick) is decided the
// same on 1, 2 and 4 ranks (ctest runs that case on each).
#include <gtest/gtest.h>
#include <mpi.h>

#include <map>
#include <string>

#include "zone_node/cluster/entity_mail.h"
#include "zone_node/cluster/halo.h"
#include "zone_node/cluster/migration.h"
#include "zone_node/systems/interactions.h"
#include "zone_node/systems/neighbourhood.h"
#include "zone_node/tick_profile.h"

namespace zonesim::zone {
namespace {

constexpr double kDt = 0.05;

/// One entity of the scenario: where it starts, where the movers take it this tick, and what
/// it must hold once the tick's mail is delivered.
struct Actor {
  std::string name;
  EntityKind kind;
  double x, z;          // at the tick's start
  double to_x, to_z;    // after the movers
  double health = 100;  // at the start
  int items = 0;        // at the start
  bool destroyed = false;  // removed before the exchange (its player logged out)
  // Expected after delivery:
  double want_health = 100;
  int want_items = 0, want_kills = 0, want_deaths = 0;
  bool taken = false;  // an item that must be gone after the tick (granted to someone)
};

// Pairs straddle the borders (x = 50, z = 50), 1 m apart, far from every other pair: each hits
// or hands to its partner only. Hit reach 1.5 m, gift reach 4 m, everyone due every tick.
std::vector<Actor> scenario() {
  std::vector<Actor> a;
  // 1. Hits across a border, both staying: each takes the other's 25.
  a.push_back({"stay-a", EntityKind::Npc, 49.5, 10, 49.5, 10, 100, 0, false, 75});
  a.push_back({"stay-b", EntityKind::Npc, 50.5, 10, 50.5, 10, 100, 0, false, 75});
  // 2. A hit whose target crosses to the hitter's zone in this tick: forwarded back, once.
  a.push_back({"hitter", EntityKind::Npc, 49.5, 30, 49.5, 30, 100, 0, false, 75});
  a.push_back({"mover", EntityKind::Npc, 50.5, 30, 49.0, 30, 100, 0, false, 75});
  // 3. A kill whose hitter crosses into the victim's zone: the victim's owner confirms it to
  //    the hitter's new owner. The victim respawns at full health.
  a.push_back({"killer", EntityKind::Npc, 49.5, 70, 51.0, 70, 100, 0, false, 75});
  a.back().want_kills = 1;
  a.push_back({"victim", EntityKind::Npc, 50.5, 70, 50.5, 70, 25, 0, false, 100});
  a.back().want_deaths = 1;
  // 4. A gift to an avatar that logged out: returned to the giver.
  a.push_back({"giver", EntityKind::Avatar, 30, 49.5, 30, 49.5, 100, 10, false, 100, 10});
  a.push_back({"gone", EntityKind::Avatar, 30, 50.5, 30, 50.5, 100, 0, true});
  // 5. A gift to an avatar crossing into the giver's zone: forwarded, received once.
  a.push_back({"donor", EntityKind::Avatar, 70, 49.5, 70, 49.5, 100, 3, false, 100, 2});
  a.push_back({"crosser", EntityKind::Avatar, 70, 50.5, 70, 48.0, 100, 0, false, 100, 1});
  // 6. A giver crossing a border whose recipient logged out: the return follows the giver.
  a.push_back({"leaver", EntityKind::Avatar, 10, 49.5, 10, 51.0, 100, 5, false, 100, 5});
  a.push_back({"absent", EntityKind::Avatar, 10, 50.5, 10, 50.5, 100, 0, true});
  // 7. A claim on an item across a border whose claimant crosses into the item's zone in this
  //    tick: the grant follows it, and the item is taken once.
  a.push_back({"loot", EntityKind::Item, 90, 50.4, 90, 50.4});
  a.back().taken = true;
  a.push_back({"claimer", EntityKind::Avatar, 90, 49.6, 88, 51, 100, 0, false, 100, 1});
  return a;
}

class EntityMailTest : public ::testing::Test {
 protected:
  void SetUp() override {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    ASSERT_TRUE(size_ == 1 || size_ == 2 || size_ == 4) << "run on 1, 2 or 4 ranks";
    layout_ =
        ZoneLayout(SceneBox{{0, 0, 0}, {100, 10, 100}}, size_ == 1 ? 1 : 2, size_ == 4 ? 2 : 1);
    settings_.enabled = true;
    settings_.hit_every_s = kDt;
    settings_.gift_every_s = kDt;
  }

  /// Runs one tick of the scenario; returns this rank's delivery figures.
  MailStats runTick(std::vector<Actor>& actors, EntityStore& store) {
    std::map<std::string, EntityId> ids;
    for (std::size_t k = 0; k < actors.size(); ++k) {
      Actor& a = actors[k];
      ids[a.name] = EntityId::make(7, k + 1);
      if (layout_.ownerOf(a.x, a.z) != rank_) continue;
      EntityRecordData r;
      r.id = ids[a.name];
      r.kind = a.kind;
      r.pos = Vec3(a.x, 0, a.z);
      r.combat.health = a.health;
      r.combat.items = a.items;
      store.add(r);
    }
    HaloExchange halo(MPI_COMM_WORLD, rank_, size_, 4.0, 1.0);
    halo.refresh(store, layout_, 0);
    EntityMail mail(MPI_COMM_WORLD, rank_, size_);
    InteractionSystem interactions(settings_, kDt, mail, rank_);
    Neighbourhood near;
    Collectives cluster;
    TickCounters counters;
    StepContext ctx{store, &halo.ghosts(), near, kDt, 0, 0.0, {}, cluster, counters};
    interactions.step(ctx);
    // The movers, and the players who logged out.
    for (const Actor& a : actors) {
      std::optional<std::size_t> i = store.indexOf(ids[a.name]);
      if (!i) continue;
      if (a.destroyed) {
        store.removeAt(*i);
        continue;
      }
      store.pos[*i] = Vec3(a.to_x, 0, a.to_z);
    }
    Migrator migrator(MPI_COMM_WORLD, rank_, size_);
    std::vector<std::vector<ForwardedInput>> forward(static_cast<std::size_t>(size_));
    MigrationResult moved = migrator.exchange(store, layout_, 0, forward);
    MailStats s = mail.deliver(
        store, moved.departed,
        [&](EntityStore& st, std::span<const EntityMessage> in, std::vector<EntityMessage>& out) {
          interactions.receive(st, in, out, counters);
        },
        [&](const EntityMessage& m, MailRefusal, std::vector<EntityMessage>& out) {
          interactions.refused(m, out, counters);
        });
    figures_ = counters;
    MailBalance balance = sumMailAudit(MPI_COMM_WORLD, mail.audit());
    EXPECT_TRUE(balance.ok()) << balance.posted.count << " posted, " << balance.settled.count
                              << " applied or refused";
    // Every survivor checked exactly once, on the rank that owns it after the tick.
    int checked = 0, survivors = 0;
    for (const Actor& a : actors) {
      if (a.destroyed) continue;
      ++survivors;
      std::optional<std::size_t> i = store.indexOf(ids[a.name]);
      if (!i) continue;
      ++checked;
      if (a.taken) {
        // Granted: marked taken (in tick 0) where it lies; the zone removes it once checkpointed.
        EXPECT_EQ(store.combat[*i].taken_at, 1u) << a.name;
        continue;
      }
      EXPECT_EQ(layout_.ownerOf(a.to_x, a.to_z), rank_) << a.name;
      const CombatData& c = store.combat[*i];
      EXPECT_EQ(c.health, a.want_health) << a.name;
      EXPECT_EQ(c.items, a.want_items) << a.name;
      EXPECT_EQ(c.kills, std::uint32_t(a.want_kills)) << a.name;
      EXPECT_EQ(c.deaths, std::uint32_t(a.want_deaths)) << a.name;
    }
    int total = 0;
    MPI_Allreduce(&checked, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_EQ(total, survivors);
    return s;
  }

  /// A figure summed over the ranks.
  static std::uint64_t sum(std::uint64_t v) {
    std::uint64_t out = 0;
    MPI_Allreduce(&v, &out, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    return out;
  }

  int rank_ = 0, size_ = 1;
  ZoneLayout layout_{SceneBox{{0, 0, 0}, {100, 10, 100}}, 2, 2};
  InteractionSettings settings_;
  TickCounters figures_;  // this rank's, from the last runTick
};

TEST_F(EntityMailTest, EveryKindIsAppliedOnceAcrossHandoff) {
  if (size_ != 4) GTEST_SKIP() << "the scenario's borders need 4 ranks";
  std::vector<Actor> actors = scenario();
  EntityStore store;
  MailStats s = runTick(actors, store);
  // Hits: 6 (3 pairs, both ways); gifts: 3; one kill confirmed; two gifts returned; one
  // claim and its grant.
  EXPECT_EQ(sum(s.posted), 14u);
  EXPECT_EQ(sum(s.applied), 12u);  // the two gifts to the logged-out avatars were refused
  EXPECT_EQ(sum(s.refused), 2u);
  // Forwarded after their target left: the hit on "mover", the gift to "crosser" and the hit
  // the killer's victim sent after it (victim -> killer, who crossed). Replies go to the rank
  // the claimant (or hitter) moved to, as the kill confirmation does: the grant to "claimer"
  // needs no forwarding.
  EXPECT_EQ(sum(s.forwarded), 3u);
  // Applied on a rank other than the one it was posted on: the hits of pair 1, the mover's
  // hit, the killer's hit, the gift returned to "giver" and the claim on "loot". The rest met
  // their target on the rank they were posted on, after it (or the reply's sender) crossed.
  EXPECT_EQ(sum(s.cross_zone), 6u);
  EXPECT_EQ(sum(figures_.pickups), 1u);
  EXPECT_GT(sum(s.bytes_sent), 0u);
}

// Two claimants of one item in the same tick, across the border x = 50 (on 2 and 4 ranks): the
// nearer wins. Two more at exactly the same distance from another item: the lower id wins.
// The item's owner alone decides, so every decomposition ends the same.
TEST_F(EntityMailTest, AContestedPickupGoesToTheNearestClaimantOnAnyRankCount) {
  settings_.hit_damage = 0;  // claims only
  settings_.gift_reach = 0;
  settings_.pickup_reach = 1.0;
  std::vector<Actor> a;
  a.push_back({"item", EntityKind::Item, 50.5, 40, 50.5, 40});
  a.back().taken = true;
  a.push_back({"far", EntityKind::Avatar, 49.6, 40, 49.6, 40, 100, 2, false, 100, 2});  // 0.9 m
  a.push_back({"near", EntityKind::Npc, 51.2, 40, 51.2, 40, 100, 0, false, 100, 1});    // 0.7 m
  a.push_back({"tied", EntityKind::Item, 60, 49.5, 60, 49.5});
  a.back().taken = true;
  a.push_back({"first", EntityKind::Avatar, 60, 50.3, 60, 50.3, 100, 0, false, 100, 1});   // 0.8 m
  a.push_back({"second", EntityKind::Avatar, 60, 48.7, 60, 48.7, 100, 0, false, 100, 0});  // 0.8 m
  a.push_back({"alone", EntityKind::Item, 20, 20, 20, 20});  // nobody near: stays
  EntityStore store;
  MailStats s = runTick(a, store);
  EXPECT_EQ(sum(figures_.pickups), 2u);
  EXPECT_EQ(sum(figures_.pickups_contested), 2u);
  EXPECT_EQ(sum(figures_.pickups_denied), 2u);
  EXPECT_EQ(sum(s.posted), 8u);  // 4 claims, 4 answers
  EXPECT_EQ(sum(s.applied), 8u);
}

TEST_F(EntityMailTest, RefusesAMessageOfUnknownKindByName) {
  // A corrupt message from another rank is an error that names what is wrong, not a crash.
  if (size_ == 1) GTEST_SKIP() << "a lone rank's messages never leave it";
  EntityMail mail(MPI_COMM_WORLD, rank_, size_);
  EntityStore store;
  EntityMessage m;
  m.from = EntityId::make(std::uint32_t(rank_), 1);
  m.to = EntityId::make(9, 9);
  m.kind = MailKind(200);
  m.to_rank = (rank_ + 1) % size_;
  mail.post(m);
  auto none = [](EntityStore&, std::span<const EntityMessage>, std::vector<EntityMessage>&) {};
  try {
    mail.deliver(store, {}, none, nullptr);
    ADD_FAILURE() << "a message of unknown kind was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown kind 200"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace zonesim::zone
