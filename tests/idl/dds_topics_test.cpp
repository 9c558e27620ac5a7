// The DDS layer: RAII handles, partitioned writers/readers and the per-cell batch type, over a
// real Cyclone DDS domain private to this test run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <thread>
#include <vector>

#include "idl/dds_entity.h"
#include "idl/dds_qos.h"
#include "idl/topics.h"
#include "support/dds_test_domain.h"
#include "zonesim.h"

namespace zonesim::dds {
namespace {

class DdsTopics : public ::testing::Test {
 protected:
  // A domain of our own: parallel tests and other runs never see our samples.
  void SetUp() override { domain_ = zonesim::testing::privateDdsDomain(); }
  int domain_ = 0;
};

/// Waits (bounded) until the writer has matched n readers.
bool waitMatched(dds_entity_t writer, std::uint32_t n) {
  for (int i = 0; i < 500; ++i) {
    dds_publication_matched_status_t st{};
    check(dds_get_publication_matched_status(writer, &st), "matched");
    if (st.current_count >= n) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST_F(DdsTopics, ABatchReachesOnlyTheReaderOfItsCellPartition) {
  Entity participant = makeParticipant(domain_);
  Topics topics = makeTopics(participant.get());
  Qos q = cellUpdateQos();
  PartitionWriter writer = makePartitionWriter(participant.get(), topics.cell_updates.get(),
                                               cellPartition(3, 4), q.get());
  PartitionReader same = makePartitionReader(participant.get(), topics.cell_updates.get(),
                                             cellPartition(3, 4), q.get());
  PartitionReader other = makePartitionReader(participant.get(), topics.cell_updates.get(),
                                              cellPartition(4, 3), q.get());
  ASSERT_TRUE(waitMatched(writer.writer.get(), 1));

  std::vector<zonesim_dds_EntityUpdate> updates(200);
  for (std::size_t i = 0; i < updates.size(); ++i) {
    updates[i].id = 1000 + i;
    updates[i].pos = {float(i), 0, 1};
  }
  zonesim_dds_CellUpdateBatch b{};
  b.cell = 7;
  b.zone = 2;
  b.tick = 99;
  b.updates._buffer = updates.data();
  b.updates._length = b.updates._maximum = std::uint32_t(updates.size());
  b.updates._release = false;
  check(dds_write(writer.writer.get(), &b), "write");

  void* samples[1] = {nullptr};
  dds_sample_info_t info[1];
  int n = 0;
  for (int i = 0; i < 500 && n == 0; ++i) {
    n = check(dds_take(same.reader.get(), samples, info, 1, 1), "take");
    if (n == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(n, 1);
  const auto* got = static_cast<const zonesim_dds_CellUpdateBatch*>(samples[0]);
  EXPECT_EQ(got->cell, 7);
  EXPECT_EQ(got->tick, 99u);
  ASSERT_EQ(got->updates._length, 200u);
  EXPECT_EQ(got->updates._buffer[199].id, 1199u);
  EXPECT_EQ(got->updates._buffer[199].pos.x, 199.0f);
  dds_return_loan(same.reader.get(), samples, n);

  samples[0] = nullptr;
  EXPECT_EQ(dds_take(other.reader.get(), samples, info, 1, 1), 0) << "another cell's reader got it";
}

TEST_F(DdsTopics, ALateKeyframeReaderGetsTheLatestKeyframe) {
  Entity participant = makeParticipant(domain_);
  Topics topics = makeTopics(participant.get());
  Qos q = cellKeyframeQos();
  PartitionWriter writer = makePartitionWriter(participant.get(), topics.cell_keyframes.get(),
                                               cellPartition(0, 0), q.get());
  for (std::uint64_t tick : {1u, 2u, 3u}) {
    zonesim_dds_CellKeyframe k{};
    k.cell = 0;
    k.zone = 1;
    k.tick = tick;
    check(dds_write(writer.writer.get(), &k), "write");
  }
  PartitionReader late = makePartitionReader(participant.get(), topics.cell_keyframes.get(),
                                             cellPartition(0, 0), q.get());
  void* samples[4] = {nullptr};
  dds_sample_info_t info[4];
  int n = 0;
  for (int i = 0; i < 500 && n == 0; ++i) {
    n = check(dds_take(late.reader.get(), samples, info, 4, 4), "take");
    if (n == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(n, 1) << "KEEP_LAST 1, TRANSIENT_LOCAL: only the newest keyframe per (cell, zone)";
  EXPECT_EQ(static_cast<const zonesim_dds_CellKeyframe*>(samples[0])->tick, 3u);
  dds_return_loan(late.reader.get(), samples, n);
}

TEST_F(DdsTopics, FailedCallsThrowWithCycloneText) {
  EXPECT_THROW(check(DDS_RETCODE_BAD_PARAMETER, "dds_something"), DdsError);
  try {
    check(DDS_RETCODE_BAD_PARAMETER, "dds_something");
  } catch (const DdsError& e) {
    EXPECT_NE(std::string(e.what()).find("dds_something"), std::string::npos);
    EXPECT_EQ(e.code(), DDS_RETCODE_BAD_PARAMETER);
  }
  EXPECT_THROW(makeParticipant(100000), DdsError);  // no such domain id
}

}  // namespace
}  // namespace zonesim::dds
