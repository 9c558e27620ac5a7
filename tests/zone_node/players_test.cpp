// The zone's player protocol against a real DDS link on a private domain, the gateways played
// by the test's writers: an avatar whose player fell silent (its gateway died) is kept for the
// orphan grace and then removed and counted; a resumed player's old session cannot remove the
// avatar its new session plays, while the new session can.
#include "zone_node/players.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "idl/dds_take.h"
#include "player_zone_fixture.h"
#include "zone_node/cluster/migration.h"

namespace zonesim::zone {
namespace {

constexpr std::uint64_t kPlayer = (std::uint64_t{3} << 32) | 9;
constexpr int kGraceTicks = 60;  // two seconds at 30 Hz

class PlayersTest : public PlayerZoneTest {
 protected:
  PlayersTest()
      : players_(scene_, 0, 1, kGraceTicks),
        despawns_(dds::makePartitionWriter(gateway_.get(), topics_.despawn_requests.get(), "",
                                           keep_all_.get())),
        ownership_(dds::makePartitionReader(gateway_.get(), topics_.ownership.get(), "",
                                            keep_all_.get())) {}

  // One tick's input and migrate phases.
  void tick() {
    ++tick_;
    PlayerZone z = zone();
    players_.input(z);
    MigrationResult none;
    players_.migrated(z, none);
  }
  // Ticks, 5 ms of wall time apart for DDS to deliver, until done() or 10 s.
  template <typename F>
  bool tickUntil(F&& done) {
    for (int i = 0; i < 2000; ++i) {
      tick();
      if (done()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }

  void requestSpawn(std::uint64_t session) { PlayerZoneTest::requestSpawn(kPlayer, session); }
  void requestDespawn(std::uint64_t session) {
    zonesim_dds_DespawnRequest r{};
    r.player_id = kPlayer;
    r.session = session;
    dds::check(dds_write(despawns_.writer.get(), &r), "write DespawnRequest");
  }
  // Announcements of the player's avatar read so far.
  std::size_t announced() {
    dds::takeAll<zonesim_dds_OwnershipEvent>(ownership_.reader.get(),
                                             [&](const zonesim_dds_OwnershipEvent& e) {
                                               if (e.player_id == kPlayer) ++announcements_;
                                             });
    return announcements_;
  }
  bool hasAvatar() const { return store_.avatarOf(kPlayer).has_value(); }

  Players players_;
  dds::PartitionWriter despawns_;
  dds::PartitionReader ownership_;
  std::size_t announcements_ = 0;
};

TEST_F(PlayersTest, ASilentPlayersAvatarIsKeptForTheGraceThenRemovedAndCounted) {
  requestSpawn(1);
  ASSERT_TRUE(tickUntil([&] { return hasAvatar(); })) << "no avatar for the spawn request";
  const std::uint64_t spawned_at = tick_;
  EntityId avatar = store_.id[*store_.avatarOf(kPlayer)];
  // No input ever comes (the gateway died): the avatar stays through the grace...
  while (tick_ < spawned_at + kGraceTicks - 1) {
    tick();
    ASSERT_TRUE(hasAvatar()) << "removed at tick " << tick_ << ", within the grace";
  }
  EXPECT_EQ(counters_.avatars_orphaned, 0u);
  // ... and is gone within the next second (the check runs once a second), counted.
  while (tick_ < spawned_at + kGraceTicks + 31) tick();
  EXPECT_FALSE(hasAvatar());
  EXPECT_EQ(counters_.avatars_orphaned, 1u);
  ASSERT_EQ(leavers_.size(), 1u) << "the publisher is told";
  EXPECT_EQ(leavers_[0].id, avatar);
  EXPECT_EQ(ledger_.count, 0u);
}

TEST_F(PlayersTest, OnlyTheNewestSessionOfAResumedPlayerRemovesItsAvatar) {
  requestSpawn(1);
  ASSERT_TRUE(tickUntil([&] { return hasAvatar() && announced() >= 1; }));
  // The player resumed at another gateway: the zone re-announces the same avatar to it.
  EntityId avatar = store_.id[*store_.avatarOf(kPlayer)];
  requestSpawn(2);
  ASSERT_TRUE(tickUntil([&] { return announced() >= 2; })) << "no re-announcement";
  EXPECT_EQ(counters_.avatars_spawned, 1u) << "the same avatar, not a second one";
  // The old session times out at the old gateway: the avatar stays.
  requestDespawn(1);
  ASSERT_TRUE(tickUntil([&] { return counters_.despawns_superseded == 1; }));
  ASSERT_TRUE(hasAvatar());
  EXPECT_EQ(store_.id[*store_.avatarOf(kPlayer)], avatar);
  // The player leaves its new session: now it goes.
  requestDespawn(2);
  ASSERT_TRUE(tickUntil([&] { return !hasAvatar(); }));
  EXPECT_EQ(counters_.despawns_superseded, 1u);
}

}  // namespace
}  // namespace zonesim::zone
