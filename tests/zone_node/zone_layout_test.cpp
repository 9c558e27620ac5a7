#include "zone_node/zone_layout.h"

#include <gtest/gtest.h>

#include "common/scene.h"
#include "zone_node/cluster/load_balancer.h"

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

namespace zonesim::zone {
namespace {

void expectPartition(const ZoneLayout& layout) {
  for (double x = -100; x < 300; x += 3.7)
    for (double z = 0; z < 200; z += 2.9) {
      int containing = 0;
      for (int r = 0; r < layout.zoneCount(); ++r) containing += layout.rect(r).contains(x, z);
      ASSERT_EQ(containing, 1) << x << "," << z;
      ASSERT_TRUE(layout.rect(layout.ownerOf(x, z)).contains(x, z));
    }
}

TEST(ZoneLayoutBalance, BoundariesMoveToEqualCostAssumingCostSpreadOverEachZone) {
  SceneBox world{{0, 0, 0}, {100, 10, 100}};
  ZoneLayout layout(world, 2, 1);
  std::vector<double> cost = {3.0, 1.0};
  layout.rebalance(cost, 1.0, 1.0);
  // Cost density 3/50 on [0, 50): half of the total (2) is reached at x = 2 / (3/50).
  EXPECT_NEAR(layout.rect(0).max_x, 100.0 / 3.0, 1e-12);
  EXPECT_NEAR(layout.rect(1).min_x, 100.0 / 3.0, 1e-12);
  ZoneLayout damped(world, 2, 1);
  damped.rebalance(cost, 0.5, 1.0);
  EXPECT_NEAR(damped.rect(0).max_x, 50.0 - 0.5 * (50.0 - 100.0 / 3.0), 1e-12);
}

TEST(ZoneLayoutBalance, RowsOfEachColumnBalanceOnTheirOwnAndZonesKeepAMinimumWidth) {
  ZoneLayout layout(kWorld, 2, 2);
  std::vector<double> cost = {100.0, 1.0, 1.0, 1.0};  // zone 0 (column 0, row 0) is a hotspot
  for (int i = 0; i < 20; ++i) layout.rebalance(cost, 1.0, 5.0);
  EXPECT_LT(layout.rect(0).area(), layout.rect(3).area());
  for (int r = 0; r < 4; ++r) {
    EXPECT_GE(layout.rect(r).max_x - layout.rect(r).min_x, 5.0 - 1e-9);
    EXPECT_GE(layout.rect(r).max_z - layout.rect(r).min_z, 5.0 - 1e-9);
  }
  expectPartition(layout);
}

TEST(ZoneLayoutBalance, BisectionGivesEveryZoneAnEqualShareOfThePoints) {
  ZoneLayout layout(kWorld, 2, 2);
  std::vector<std::pair<double, double>> points;
  for (int i = 0; i < 1000; ++i) points.emplace_back(-100 + 0.1 * i, 0.15 * i);  // one diagonal
  for (int i = 0; i < 1000; ++i) points.emplace_back(250 + 0.01 * i, 190 - 0.01 * i);
  layout.bisect(points);
  std::vector<int> count(4, 0);
  for (auto [x, z] : points) ++count[std::size_t(layout.ownerOf(x, z))];
  for (int c : count) EXPECT_EQ(c, 500);
  expectPartition(layout);
}

TEST(ZoneLayoutBalance, HysteresisStartsAboveTheThresholdAndStopsBelowTheMidpoint) {
  EXPECT_FALSE(balancingActive(false, 1.2, 1.3));
  EXPECT_TRUE(balancingActive(false, 1.31, 1.3));
  EXPECT_TRUE(balancingActive(true, 1.2, 1.3));    // still above 1.15: keep going
  EXPECT_FALSE(balancingActive(true, 1.14, 1.3));  // settled
  EXPECT_DOUBLE_EQ(imbalanceOf({1, 1, 1, 1}), 1.0);
  EXPECT_DOUBLE_EQ(imbalanceOf({4, 0, 0, 0}), 4.0);
  EXPECT_DOUBLE_EQ(imbalanceOf({0, 0}), 1.0);
}

}  // namespace
}  // namespace zonesim::zone
