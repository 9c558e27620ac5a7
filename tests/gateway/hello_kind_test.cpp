// The kind a Hello carries: a Hello without one is a walker's, byte for byte what it was before
// kinds; a listed kind reaches the session and the zones' spawn request; any kind the scene does
// not list opens nothing and is counted as unknown_kind.
#include <gtest/gtest.h>

#include "gateway/datagram_handler.h"

namespace zonesim::gateway {
namespace {

constexpr std::uint8_t kRider = std::uint8_t(PlayerKindId::Rider);
constexpr std::uint8_t kFlyer = std::uint8_t(PlayerKindId::Flyer);

class HelloKindTest : public ::testing::Test {
 protected:
  // The handler of a scene with walkers and flyers, but no riders.
  HelloKindTest() : sessions_(2, 8), handler_(sessions_, config()) {}

  static HandlerConfig config() {
    HandlerConfig c;
    c.world = {{-50, 0, -50}, {50, 10, 50}};
    c.kinds = (1u << 0) | (1u << kFlyer);
    return c;
  }

  void feed(const Bytes& b, const Endpoint& from = kClient) {
    out_.clear();
    handler_.handle(b, from, ++now_, out_);
  }

  static inline const Endpoint kClient = Endpoint::loopback(45100);
  SessionTable sessions_;
  DatagramHandler handler_;
  Outbox out_;
  std::int64_t now_ = 0;
};

TEST_F(HelloKindTest, AHelloWithoutAKindIsAWalkersAsBefore) {
  EXPECT_EQ(encodeHello(7, "p"), encodeHello(7, "p", {}, 0)) << "a walker writes no kind field";
  feed(encodeHello(7, "p"));
  ASSERT_EQ(out_.spawns.size(), 1u);
  EXPECT_EQ(out_.spawns[0].kind, 0);
  EXPECT_EQ(sessions_.get(*sessions_.findByHello(kClient, 7))->kind, PlayerKindId::Walker);
}

TEST_F(HelloKindTest, AListedKindReachesTheSessionAndTheSpawnRequest) {
  feed(encodeHello(8, "p", {}, kFlyer));
  ASSERT_EQ(out_.spawns.size(), 1u);
  EXPECT_EQ(out_.spawns[0].kind, kFlyer);
  EXPECT_EQ(sessions_.get(*sessions_.findByHello(kClient, 8))->kind, PlayerKindId::Flyer);
  EXPECT_EQ(handler_.drops().total(), 0u);
}

TEST_F(HelloKindTest, KindsTheSceneDoesNotListAreRefusedAndCounted) {
  // A rider (a kind, but not this scene's), a byte past the last kind and the largest byte.
  for (std::uint8_t kind : {kRider, std::uint8_t(kPlayerKindCount), std::uint8_t(255)})
    feed(encodeHello(9 + kind, "p", {}, kind));
  EXPECT_EQ(handler_.drops()[DropReason::UnknownKind], 3u);
  EXPECT_EQ(sessions_.size(), 0u);
  EXPECT_TRUE(out_.spawns.empty());
  EXPECT_EQ(handler_.accepted(), 0u);
  EXPECT_STREQ(dropReasonName(DropReason::UnknownKind), "unknown_kind");
}

}  // namespace
}  // namespace zonesim::gateway
