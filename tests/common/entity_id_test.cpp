// Entity ids: rank and counter survive packing, allocators never repeat, and the id-set
// digest is the same however the set is ordered or split over ranks.

#include "common/entity_id.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

namespace zonesim {
namespace {

TEST(EntityId, MakeRoundTripsRankAndCounter) {
  const std::uint32_t ranks[] = {0, 1, 7, 0xffff};
  const std::uint64_t counters[] = {1, 2, 0xabcdef, EntityId::kCounterMask};
  for (std::uint32_t rank : ranks) {
    for (std::uint64_t counter : counters) {
      EntityId id = EntityId::make(rank, counter);
      EXPECT_EQ(id.creatorRank(), rank);
      EXPECT_EQ(id.counter(), counter);
      EXPECT_TRUE(id);
    }
  }
  EXPECT_FALSE(EntityId{});
  EXPECT_EQ(toString(EntityId::make(3, 42)), "3:42");
}

TEST(EntityId, OrderFollowsRankThenCounter) {
  EXPECT_LT(EntityId::make(1, 999), EntityId::make(2, 1));
  EXPECT_LT(EntityId::make(2, 1), EntityId::make(2, 2));
}

TEST(EntityIdAllocator, IssuesUniqueIdsAcrossRanks) {
  std::set<EntityId> seen;
  for (std::uint32_t rank = 0; rank < 4; ++rank) {
    EntityIdAllocator alloc(rank);
    for (int i = 0; i < 1000; ++i) {
      EntityId id = alloc.next();
      EXPECT_NE(id.value, 0u);
      EXPECT_EQ(id.creatorRank(), rank);
      EXPECT_TRUE(seen.insert(id).second) << toString(id);
    }
    EXPECT_EQ(alloc.issued(), 1000u);
  }
  EXPECT_EQ(seen.size(), 4000u);
}

std::vector<EntityId> sampleIds() {
  std::vector<EntityId> ids;
  for (std::uint32_t rank = 0; rank < 3; ++rank) {
    EntityIdAllocator alloc(rank);
    for (int i = 0; i < 300; ++i) ids.push_back(alloc.next());
  }
  return ids;
}

IdSetDigest digestOf(const std::vector<EntityId>& ids) {
  IdSetDigest d;
  for (EntityId id : ids) d.add(id);
  return d;
}

TEST(IdSetDigest, IsIndependentOfOrder) {
  std::vector<EntityId> ids = sampleIds();
  IdSetDigest in_order = digestOf(ids);
  std::mt19937 gen(5);
  std::shuffle(ids.begin(), ids.end(), gen);
  EXPECT_EQ(digestOf(ids), in_order);
  std::reverse(ids.begin(), ids.end());
  EXPECT_EQ(digestOf(ids), in_order);
  EXPECT_EQ(in_order.count, ids.size());
}

TEST(IdSetDigest, PartsMergeToTheWhole) {
  std::vector<EntityId> ids = sampleIds();
  IdSetDigest whole = digestOf(ids);
  // Split as if over ranks: every fourth id to each of four parts, merged in another order.
  IdSetDigest parts[4];
  for (std::size_t i = 0; i < ids.size(); ++i) parts[(i * 7) % 4].add(ids[i]);
  IdSetDigest merged;
  for (int p : {2, 0, 3, 1}) merged.merge(parts[p]);
  EXPECT_EQ(merged, whole);
}

TEST(IdSetDigest, NoticesALostOrSwappedId) {
  std::vector<EntityId> ids = sampleIds();
  IdSetDigest whole = digestOf(ids);
  std::vector<EntityId> lost(ids.begin() + 1, ids.end());
  EXPECT_NE(digestOf(lost), whole);
  std::vector<EntityId> swapped = ids;
  swapped[10] = EntityId::make(9, 1);
  IdSetDigest d = digestOf(swapped);
  EXPECT_EQ(d.count, whole.count);
  EXPECT_NE(d.hash, whole.hash);
}

}  // namespace
}  // namespace zonesim
