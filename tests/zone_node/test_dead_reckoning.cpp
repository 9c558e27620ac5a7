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
  // Moving exactly as predicted: no update until the heartbeat.
  EXPECT_FALSE(needsUpdate(s, Vec3(2, 0, 0), 12.0, cfg));
  EXPECT_TRUE(needsUpdate(s, Vec3(5, 0, 0), 15.0, cfg));
  // Turned: 0.4 m off is tolerated, 0.6 m is not.
  EXPECT_FALSE(needsUpdate(s, Vec3(2, 0, 0.4), 12.0, cfg));
  EXPECT_TRUE(needsUpdate(s, Vec3(2, 0, 0.6), 12.0, cfg));
  EXPECT_EQ(predictFirstOrder(s, 11.5), Vec3(1.5, 0, 0));
}

}  // namespace
}  // namespace zonesim::zone
