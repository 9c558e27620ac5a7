#include "zone_node/population.h"

#include <gtest/gtest.h>

#include <set>

#include "zone_node/zone_fixture.h"
#include "zone_node/zone_layout.h"

namespace zonesim::zone {
namespace {

TEST(Population, InitialEntitiesAreTheSameWhateverTheRankCount) {
  Scene s = testing::npcScene(500);
  std::vector<EntityRecordData> all;
  forEachInitialEntity(s, [&](const EntityRecordData& r) { all.push_back(r); });
  ASSERT_EQ(all.size(), 500u);
  std::set<std::uint64_t> ids;
  for (const auto& r : all) {
    ids.insert(r.id.value);
    EXPECT_EQ(r.id.creatorRank(), kSceneCreator);
    EXPECT_GE(r.pos.x(), 0);
    EXPECT_LT(r.pos.x(), 200);
  }
  EXPECT_EQ(ids.size(), 500u);

  // Every partition into zones keeps each entity exactly once.
  for (int ranks : {1, 2, 4}) {
    ZoneLayout layout = ZoneLayout::forRanks(s, ranks);
    std::size_t kept = 0;
    for (int r = 0; r < ranks; ++r)
      forEachInitialEntity(
          s, [&](const EntityRecordData& e) { kept += layout.ownerOf(e.pos.x(), e.pos.z()) == r; });
    EXPECT_EQ(kept, all.size()) << ranks << " ranks";
  }
}

TEST(Population, SameSeedSameWorldOtherSeedOtherWorld) {
  std::vector<Vec3> a, b, c;
  forEachInitialEntity(testing::npcScene(50, 1),
                       [&](const EntityRecordData& r) { a.push_back(r.pos); });
  forEachInitialEntity(testing::npcScene(50, 1),
                       [&](const EntityRecordData& r) { b.push_back(r.pos); });
  forEachInitialEntity(testing::npcScene(50, 2),
                       [&](const EntityRecordData& r) { c.push_back(r.pos); });
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

}  // namespace
}  // namespace zonesim::zone
