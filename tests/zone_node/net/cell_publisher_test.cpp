// The publish phase over a real Cyclone DDS domain private to this test: cells nobody reads are
// not encoded, a moved entity gets an update, a cell change is a leave there and an enter here,
// and a subscribed cell gets a keyframe every keyframe_every ticks.
#include "zone_node/net/cell_publisher.h"

#include <gtest/gtest.h>

#include <optional>
#include <utility>
#include <vector>

#include "idl/dds_qos.h"
#include "support/dds_test_domain.h"
#include "zone_node/zone_fixture.h"

namespace zonesim::zone {
namespace {

constexpr int kKeyframeEvery = 4;
constexpr dds_duration_t kWait = DDS_SECS(10);  // a bound on a wait, not a timing claim

/// What one CellUpdateBatch carried.
struct Batch {
  std::uint64_t tick = 0;
  std::vector<std::uint64_t> enters, updates;
  std::vector<std::pair<std::uint64_t, std::uint8_t>> leaves;
};

/// A reader of one cell's updates or keyframes, waiting on a waitset for samples.
class CellReader {
 public:
  CellReader(dds_entity_t participant, dds_entity_t topic, int ix, int iz, const dds_qos_t* qos)
      : r_(dds::makePartitionReader(participant, topic, dds::cellPartition(ix, iz), qos)),
        waitset_(dds_create_waitset(participant)),
        data_(dds_create_readcondition(r_.reader.get(), DDS_ANY_STATE)) {
    dds::check(dds_waitset_attach(waitset_.get(), data_.get(), 0), "dds_waitset_attach");
  }

  /// True once a writer of this cell is matched (waits on the reader's status, bounded).
  bool matched() const {
    dds_entity_t reader = r_.reader.get();
    dds::check(dds_set_status_mask(reader, DDS_SUBSCRIPTION_MATCHED_STATUS), "dds_set_status_mask");
    dds::Entity ws(dds_create_waitset(dds_get_participant(reader)));
    dds::check(dds_waitset_attach(ws.get(), reader, 0), "dds_waitset_attach");
    dds_subscription_matched_status_t st{};
    dds::check(dds_get_subscription_matched_status(reader, &st), "matched");
    if (st.current_count == 0) {
      dds_waitset_wait(ws.get(), nullptr, 0, kWait);
      dds::check(dds_get_subscription_matched_status(reader, &st), "matched");
    }
    return st.current_count > 0;
  }

  std::optional<Batch> takeBatch() {
    std::optional<Batch> out;
    take([&](const void* s) {
      const auto* b = static_cast<const zonesim_dds_CellUpdateBatch*>(s);
      Batch got;
      got.tick = b->tick;
      for (std::uint32_t k = 0; k < b->enters._length; ++k)
        got.enters.push_back(b->enters._buffer[k].id);
      for (std::uint32_t k = 0; k < b->updates._length; ++k)
        got.updates.push_back(b->updates._buffer[k].id);
      for (std::uint32_t k = 0; k < b->leaves._length; ++k)
        got.leaves.emplace_back(b->leaves._buffer[k].id, b->leaves._buffer[k].reason);
      out = got;
    });
    return out;
  }

  /// The tick and entity ids of the next keyframe.
  std::optional<std::pair<std::uint64_t, std::vector<std::uint64_t>>> takeKeyframe() {
    std::optional<std::pair<std::uint64_t, std::vector<std::uint64_t>>> out;
    take([&](const void* s) {
      const auto* k = static_cast<const zonesim_dds_CellKeyframe*>(s);
      std::vector<std::uint64_t> ids;
      for (std::uint32_t e = 0; e < k->entities._length; ++e)
        ids.push_back(k->entities._buffer[e].id);
      out = std::make_pair(k->tick, ids);
    });
    return out;
  }

 private:
  template <typename F>
  void take(F&& f) {
    if (dds_waitset_wait(waitset_.get(), nullptr, 0, kWait) <= 0) return;
    void* samples[1] = {nullptr};
    dds_sample_info_t info[1];
    int n = dds::check(dds_take(r_.reader.get(), samples, info, 1, 1), "dds_take");
    if (n == 1 && info[0].valid_data) f(samples[0]);
    if (n > 0) dds_return_loan(r_.reader.get(), samples, n);
  }

  dds::PartitionReader r_;
  dds::Entity waitset_, data_;
};

class CellPublisherTest : public ::testing::Test {
 protected:
  CellPublisherTest()
      : participant_(dds::makeParticipant(zonesim::testing::privateDdsDomain())),
        topics_(dds::makeTopics(participant_.get())),
        scene_(sceneWithKeyframes()),
        grid_(scene_.world, scene_.interest_cell_size),
        publisher_(participant_.get(), topics_, grid_, 0, scene_, 0) {
    publisher_.cover(scene_.world.min.x, scene_.world.min.z, scene_.world.max.x,
                     scene_.world.max.z);
  }

  static Scene sceneWithKeyframes() {
    Scene s = testing::npcScene(0);  // 200 m x 200 m, cells of 50 m: 4 x 4
    s.keyframe_every = kKeyframeEvery;
    return s;
  }

  /// A standing NPC at (x, z); returns its id.
  EntityId addNpc(double x, double z) {
    EntityRecordData e;
    e.id = EntityId::make(0, ++next_);
    e.kind = EntityKind::Npc;
    e.pos = Vec3(x, 0, z);
    store_.add(e);
    return e.id;
  }

  PublishStats publish(std::vector<Departure> leavers = {}) {
    ++tick_;
    return publisher_.publish(store_, leavers, tick_, double(tick_) * scene_.dt);
  }

  CellReader updates(int ix, int iz) {
    dds::Qos q = dds::cellUpdateQos();
    return CellReader(participant_.get(), topics_.cell_updates.get(), ix, iz, q.get());
  }
  CellReader keyframes(int ix, int iz) {
    dds::Qos q = dds::cellKeyframeQos();
    return CellReader(participant_.get(), topics_.cell_keyframes.get(), ix, iz, q.get());
  }

  dds::Entity participant_;
  dds::Topics topics_;
  Scene scene_;
  InterestGrid grid_;
  CellPublisher publisher_;
  EntityStore store_;
  std::uint64_t tick_ = 0, next_ = 0;
};

// A reader's first tick is a keyframe of its cell (CellPublisher::refreshSubscriptions); the
// enters, updates and leaves follow from the next tick on.
TEST_F(CellPublisherTest, CellsWithNoSubscriberAreNotEncoded) {
  CellReader read = updates(0, 0);
  ASSERT_TRUE(read.matched());
  addNpc(10, 10);    // cell (0, 0)
  addNpc(190, 190);  // cell (3, 3): nobody reads it
  PublishStats first = publish();
  EXPECT_EQ(first.subscribed_cells, 1u);
  EXPECT_EQ(first.states_computed, 1u);  // the entity nobody reads costs no state
  EXPECT_EQ(first.keyframes, 1u);
  EXPECT_EQ(first.cells_written, 0u);
  EXPECT_GT(store_.dr[0].time, 0.0);  // quantised and marked sent
  EXPECT_EQ(store_.dr[1].time, 0.0);  // never encoded

  EntityId seen = addNpc(20, 20);
  addNpc(180, 170);
  PublishStats s = publish();
  EXPECT_EQ(s.states_computed, 2u);
  EXPECT_EQ(s.cells_written, 1u);
  EXPECT_EQ(s.enters, 1u);
  EXPECT_EQ(s.keyframes, 0u);
  std::optional<Batch> b = read.takeBatch();
  ASSERT_TRUE(b);
  EXPECT_EQ(b->tick, tick_);
  EXPECT_EQ(b->enters, std::vector<std::uint64_t>{seen.value});
  EXPECT_EQ(store_.dr[1].time, 0.0);
  EXPECT_EQ(store_.dr[3].time, 0.0);
}

TEST_F(CellPublisherTest, OnlyEntitiesInOrNextToReadCellsKeepAMotionHistory) {
  CellReader read = updates(0, 0);
  ASSERT_TRUE(read.matched());
  addNpc(10, 10);    // cell (0, 0): read
  addNpc(60, 60);    // cell (1, 1): next to it
  addNpc(110, 10);   // cell (2, 0): two cells away
  addNpc(190, 190);  // cell (3, 3)
  PublishStats first = publish();
  EXPECT_EQ(first.states_computed, 1u);
  EXPECT_EQ(first.histories_kept, 2u);
  EXPECT_TRUE(store_.dr[1].has_last);
  EXPECT_FALSE(store_.dr[2].has_last);
  EXPECT_FALSE(store_.dr[3].has_last);
  // The far entity walks next to the read cell: from then on its history is kept, and when it
  // crosses in, its first state comes from that history.
  store_.pos[2] = Vec3(90, 0, 10);  // cell (1, 0)
  PublishStats second = publish();
  EXPECT_EQ(second.histories_kept, 3u);
  EXPECT_TRUE(store_.dr[2].has_last);
  EXPECT_EQ(store_.dr[2].vel_count, 1);
  store_.pos[2] = Vec3(45, 0, 10);  // cell (0, 0)
  PublishStats third = publish();
  EXPECT_EQ(third.states_computed, 2u);
  EXPECT_EQ(third.enters, 1u);
  EXPECT_EQ(store_.dr[2].vel_count, 2);
}

TEST_F(CellPublisherTest, AMovedEntityGetsAnUpdateAndAStillOneNone) {
  CellReader read = updates(0, 0);
  ASSERT_TRUE(read.matched());
  EntityId moving = addNpc(10, 10);
  addNpc(30, 30);
  ASSERT_EQ(publish().keyframes, 1u);

  PublishStats still = publish();
  EXPECT_EQ(still.updates, 0u);
  EXPECT_EQ(still.suppressed, 2u);
  EXPECT_EQ(still.cells_written, 0u);

  store_.pos[0] += Vec3(3, 0, 0);  // far beyond the 0.5 m dead-reckoning threshold
  PublishStats moved = publish();
  EXPECT_EQ(moved.updates, 1u);
  EXPECT_EQ(moved.position_updates, 1u);
  EXPECT_EQ(moved.suppressed, 1u);
  std::optional<Batch> b = read.takeBatch();
  ASSERT_TRUE(b);
  EXPECT_EQ(b->tick, tick_);
  EXPECT_EQ(b->updates, std::vector<std::uint64_t>{moving.value});
  EXPECT_TRUE(b->enters.empty());
}

TEST_F(CellPublisherTest, ACellChangeIsALeaveThereAndAnEnterHere) {
  CellReader from = updates(0, 0), to = updates(1, 0);
  ASSERT_TRUE(from.matched());
  ASSERT_TRUE(to.matched());
  EntityId walker = addNpc(45, 10);
  ASSERT_EQ(publish().keyframes, 2u);

  store_.pos[0].x() = 55;  // into cell (1, 0)
  PublishStats s = publish();
  EXPECT_EQ(s.leaves, 1u);
  EXPECT_EQ(s.enters, 1u);
  EXPECT_EQ(s.cells_written, 2u);
  std::optional<Batch> left = from.takeBatch(), entered = to.takeBatch();
  ASSERT_TRUE(left);
  ASSERT_TRUE(entered);
  ASSERT_EQ(left->leaves.size(), 1u);
  EXPECT_EQ(left->leaves[0].first, walker.value);
  EXPECT_EQ(left->leaves[0].second, zonesim_dds_LEAVE_MOVED_CELL);
  EXPECT_TRUE(left->enters.empty());
  EXPECT_EQ(entered->enters, std::vector<std::uint64_t>{walker.value});
  EXPECT_TRUE(entered->leaves.empty());
}

TEST_F(CellPublisherTest, ASubscribedCellGetsAKeyframeEveryKTicks) {
  CellReader read = keyframes(0, 0);
  ASSERT_TRUE(read.matched());
  EntityId a = addNpc(10, 10), b = addNpc(20, 40);
  addNpc(150, 150);  // an unread cell: never keyframed

  std::vector<std::uint64_t> keyframe_ticks;
  for (int t = 0; t < 3 * kKeyframeEvery; ++t) {
    PublishStats s = publish();
    EXPECT_LE(s.keyframes, 1u);
    if (s.keyframes == 0) continue;
    keyframe_ticks.push_back(tick_);
    auto k = read.takeKeyframe();
    ASSERT_TRUE(k);
    EXPECT_EQ(k->first, tick_);
    EXPECT_EQ(k->second, (std::vector<std::uint64_t>{a.value, b.value}));
  }
  // The first tick's for the new reader, then every kKeyframeEvery ticks.
  EXPECT_EQ(keyframe_ticks, (std::vector<std::uint64_t>{1, 4, 8, 12}));
}

// With no reader on any cell the zone tracks nothing (the publish phase costs two counter reads
// per cell); the first reader still gets a keyframe of its cell, and an entity that changed
// cells meanwhile sends no leave for a cell nobody saw it in.
TEST_F(CellPublisherTest, WithNoReaderAnywhereNothingIsTrackedAndAFirstReaderGetsItsKeyframe) {
  EntityId walker = addNpc(60, 10);  // cell (1, 0)
  addNpc(190, 190);                  // cell (3, 3)
  for (int t = 0; t < 5; ++t) {
    PublishStats s = publish();
    EXPECT_EQ(s.subscribed_cells, 0u);
    EXPECT_EQ(s.states_computed, 0u);
    EXPECT_EQ(s.keyframes + s.cells_written, 0u);
  }
  EXPECT_EQ(store_.dr[0].cell, -1);  // never tracked
  EXPECT_FALSE(store_.dr[0].has_last);
  store_.pos[0] = Vec3(10, 0, 10);  // moved into cell (0, 0) while nobody read
  store_.vel[0] = Vec3(-1, 0, 0);
  CellReader fresh = keyframes(0, 0), left = updates(1, 0);
  ASSERT_TRUE(fresh.matched());
  ASSERT_TRUE(left.matched());
  PublishStats s = publish();
  EXPECT_EQ(s.subscribed_cells, 2u);
  EXPECT_EQ(s.keyframes, 2u);  // each new reader's cell
  EXPECT_EQ(s.leaves, 0u);     // nobody saw the walker in cell (1, 0)
  EXPECT_EQ(s.states_computed, 1u);
  auto k = fresh.takeKeyframe();
  ASSERT_TRUE(k);
  EXPECT_EQ(k->second, std::vector<std::uint64_t>{walker.value});
  EXPECT_EQ(store_.dr[0].cell, grid_.cellOf(10, 10));
  // From the next tick on the walker is tracked again: its motion history restarts.
  publish();
  EXPECT_TRUE(store_.dr[0].has_last);
  EXPECT_EQ(store_.dr[0].vel_count, 2);
}

}  // namespace
}  // namespace zonesim::zone
