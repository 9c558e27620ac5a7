#include <gtest/gtest.h>

#include "zone_node/net/dead_reckoning.h"

namespace zonesim::zone {
namespace {

TEST(DeadReckoning, UpdatesOnlyWhenThePredictionDriftsOrTheHeartbeatExpires) {
  DeadReckoning cfg;
  cfg.position_threshold = 0.5;
  cfg.heartbeat_seconds = 5;
  DeadReckoningState s;
  markSent(s, Vec3(0, 0, 0), Vec3(1, 0, 0), 10.0);
  const EntityId id = EntityId::make(3, 99);
  // Moving exactly as predicted: no update until the heartbeat (between 3.75 and 5 s).
  EXPECT_FALSE(needsUpdate(s, id, Vec3(2, 0, 0), 12.0, cfg));
  EXPECT_FALSE(needsUpdate(s, id, Vec3(3.7, 0, 0), 13.7, cfg));
  EXPECT_TRUE(needsUpdate(s, id, Vec3(5, 0, 0), 15.0, cfg));
  // Turned: 0.4 m off is tolerated, 0.6 m is not.
  EXPECT_FALSE(needsUpdate(s, id, Vec3(2, 0, 0.4), 12.0, cfg));
  EXPECT_TRUE(needsUpdate(s, id, Vec3(2, 0, 0.6), 12.0, cfg));
  EXPECT_EQ(predictFirstOrder(s, 11.5), Vec3(1.5, 0, 0));
}

TEST(DeadReckoning, HeartbeatsOfEntitiesSentTogetherSpreadOverAQuarterPeriod) {
  DeadReckoning cfg;
  cfg.heartbeat_seconds = 4;
  double lo = 1e9, hi = 0;
  int first_quarter = 0;
  for (std::uint64_t c = 1; c <= 10000; ++c) {
    double p = heartbeatPeriod(EntityId::make(0xFFFF, c), cfg);
    lo = std::min(lo, p);
    hi = std::max(hi, p);
    first_quarter += p < 3.25;
  }
  EXPECT_GE(lo, 3.0);
  EXPECT_LT(hi, 4.0);
  EXPECT_NEAR(first_quarter / 10000.0, 0.25, 0.03);  // uniform over [3, 4)
}

}  // namespace
}  // namespace zonesim::zone
