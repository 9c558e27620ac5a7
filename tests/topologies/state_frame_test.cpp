#include "topologies/state_frame.h"

#include <gtest/gtest.h>

#include "common/scene.h"

namespace zonesim::topo {
namespace {

constexpr std::uint64_t kToken = 0x0123456789abcdefull;

dr::StateCodec arenaCodec() {
  dr::CodecParams p;
  p.world_max[0] = 40, p.world_max[1] = 10, p.world_max[2] = 40;
  p.cell_size = 20;
  return dr::StateCodec(p);
}

TEST(StateFrame, SixteenAvatarsRoundTripInOneFrame) {
  dr::StateCodec codec = arenaCodec();
  std::vector<dr::WireEntity> in;
  for (std::uint32_t p = 0; p < 16; ++p) {
    dr::WireEntity e;
    e.id = avatarId(p);
    e.kind = kAvatarKind;
    e.tick = 500;
    e.state.pos = {1.0 + 2 * p, 0, 30.0 - p};
    e.state.vel = {1.5, 0, -2.25};
    e.cell = (e.state.pos.z >= 20 ? 2 : 0) + (e.state.pos.x >= 20 ? 1 : 0);
    in.push_back(e);
  }
  std::vector<std::uint8_t> frame = encodeStateFrame(codec, kToken, 7, 500, in);
  DecodedStates d = decodeStateFrame(codec, frame, kToken);
  ASSERT_FALSE(d.drop);
  ASSERT_EQ(d.entities.size(), 16u);
  for (std::size_t i = 0; i < in.size(); ++i) {
    EXPECT_EQ(playerOf(d.entities[i].id), i);
    EXPECT_NEAR(d.entities[i].state.pos.x, in[i].state.pos.x, 1.0 / 512);
    EXPECT_NEAR(d.entities[i].state.vel.z, in[i].state.vel.z, 1.0 / 128);
  }
}

TEST(StateFrame, AnotherGamesFrameIsDropped) {
  dr::StateCodec codec = arenaCodec();
  dr::WireEntity e;
  e.id = 1;
  e.tick = 3;
  std::vector<std::uint8_t> frame = encodeStateFrame(codec, kToken, 1, 3, {&e, 1});
  EXPECT_EQ(decodeStateFrame(codec, frame, kToken + 1).drop, gateway::DropReason::BadChecksum);
}

}  // namespace
}  // namespace zonesim::topo
