#include <gtest/gtest.h>

#include "zone_node/zone_layout.h"

namespace zonesim::zone {
namespace {

const SceneBox kWorld{{-100, 0, 0}, {300, 50, 200}};

TEST(ZoneLayout, EveryPointHasExactlyTheOwnerWhoseRectContainsIt) {
  ZoneLayout layout(kWorld, 3, 2);
  for (double x = -100; x < 300; x += 7.3)
    for (double z = 0; z < 200; z += 5.1) {
      int owner = layout.ownerOf(x, z);
      int containing = 0;
      for (int r = 0; r < layout.zoneCount(); ++r) containing += layout.rect(r).contains(x, z);
      EXPECT_EQ(containing, 1) << x << "," << z;
      EXPECT_TRUE(layout.rect(owner).contains(x, z)) << x << "," << z;
    }
}

TEST(ZoneLayout, PointsOutsideTheWorldBelongToTheEdgeZone) {
  ZoneLayout layout(kWorld, 2, 2);
  EXPECT_EQ(layout.ownerOf(-500, -500), 0);
  EXPECT_EQ(layout.ownerOf(1000, 1000), 3);
  EXPECT_EQ(layout.ownerOf(300, 0), 1);  // the max edge is outside [min, max)
}

TEST(ZoneLayout, ForRanksUsesTheSceneGridOrANearlySquareOne) {
  Scene s;
  s.world = kWorld;
  s.zones.columns = 4;
  s.zones.rows = 1;
  EXPECT_EQ(ZoneLayout::forRanks(s, 4).columns(), 4);
  ZoneLayout two = ZoneLayout::forRanks(s, 2);
  EXPECT_EQ(two.columns() * two.rows(), 2);
  ZoneLayout six = ZoneLayout::forRanks(s, 6);
  EXPECT_EQ(six.columns(), 3);
  EXPECT_EQ(six.rows(), 2);
  EXPECT_EQ(ZoneLayout::forRanks(s, 1).zoneCount(), 1);
}

}  // namespace
}  // namespace zonesim::zone
