#include "dr/state_codec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "dr/bit_stream.h"

namespace zonesim::dr {
namespace {

CodecParams params() {
  CodecParams p;
  p.world_min[0] = -500, p.world_min[1] = 0, p.world_min[2] = -300;
  p.world_max[0] = 500, p.world_max[1] = 100, p.world_max[2] = 300;
  p.cell_size = 50;
  return p;
}

Q4 randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return normalized({n(rng), n(rng), n(rng), n(rng)});
}

int cellOf(const StateCodec& c, double x, double z) {
  const CodecParams& p = c.params();
  int ix = std::clamp(int(std::floor((x - p.world_min[0]) / p.cell_size)), 0, c.columns() - 1);
  int iz = std::clamp(int(std::floor((z - p.world_min[2]) / p.cell_size)), 0,
                      c.cellCount() / c.columns() - 1);
  return iz * c.columns() + ix;
}

TEST(StateCodec, BitStreamRoundTripsAndRefusesOverruns) {
  BitWriter w;
  w.write(5, 3);
  w.writeVar(0);
  w.writeVar(~std::uint64_t{0});
  w.write(0x1234, 13);
  BitReader r(w.bytes());
  EXPECT_EQ(r.read(3), 5u);
  EXPECT_EQ(r.readVar(), 0u);
  EXPECT_EQ(r.readVar(), ~std::uint64_t{0});
  EXPECT_EQ(r.read(13), 0x1234u);
  EXPECT_TRUE(r.ok());
  r.read(16);
  EXPECT_FALSE(r.ok());
  // varBits says what writeVar takes.
  for (std::uint64_t v :
       {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{77}, ~std::uint64_t{0}}) {
    BitWriter one;
    one.writeVar(v);
    EXPECT_EQ(int(one.bits()), varBits(v)) << v;
  }
}

TEST(StateCodec, RoundTripErrorsStayWithinHalfAStep) {
  StateCodec codec(params());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(-500, 500), y(0, 100), z(-300, 300), v(-30, 30);
  double worst_pos = 0, worst_vel = 0, worst_acc = 0, worst_rot = 0, worst_w = 0;
  for (int i = 0; i < 20000; ++i) {
    State s;
    s.pos = {x(rng), y(rng), z(rng)};
    s.vel = {v(rng), v(rng), v(rng)};
    s.acc = {v(rng), v(rng), v(rng)};
    s.rot = randomRotation(rng);
    s.angvel = {v(rng) / 3, v(rng) / 3, v(rng) / 3};
    State q = codec.roundTrip(s, {Order::Second, Spin::Rotating}, cellOf(codec, s.pos.x, s.pos.z));
    for (auto [a, b, worst] : {std::tuple{s.pos, q.pos, &worst_pos},
                               {s.vel, q.vel, &worst_vel},
                               {s.acc, q.acc, &worst_acc},
                               {s.angvel, q.angvel, &worst_w}})
      *worst = std::max({*worst, std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)});
    worst_rot = std::max(worst_rot, angleBetween(s.rot, q.rot));
  }
  const CodecParams& p = codec.params();
  // Uniform quantisers: at most half a step per axis.
  EXPECT_LE(worst_pos, p.position_resolution / 2 + 1e-12);
  EXPECT_LE(worst_vel, p.velocity_resolution / 2 + 1e-12);
  EXPECT_LE(worst_acc, p.acceleration_resolution / 2 + 1e-12);
  EXPECT_LE(worst_w, p.angular_velocity_resolution / 2 + 1e-12);
  // Smallest three with step d: each kept component is off by <= d/2, the rebuilt one by
  // <= 1.5 d (it is >= 1/2), so the quaternion is off by <= sqrt(3) d and the angle by about
  // twice that.
  EXPECT_LE(worst_rot, 2 * std::sqrt(3.0) * codec.rotationStep());
  EXPECT_LT(worst_rot * 180 / 3.14159265358979, 0.25);  // far inside a 3 degree threshold
  // And the bounds are not vacuous: the errors reach a good part of them.
  EXPECT_GT(worst_pos, p.position_resolution / 4);
}

TEST(StateCodec, RequantisingTheDecodedFloatsGivesTheSameState) {
  // The zone publishes floats of its round-tripped state; the gateway quantises them again.
  StateCodec codec(params());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> x(-500, 500), z(-300, 300), v(-20, 20);
  Model m{Order::Second, Spin::Rotating};
  for (int i = 0; i < 5000; ++i) {
    State s;
    s.pos = {x(rng), 1.5, z(rng)};
    s.vel = {v(rng), 0, v(rng)};
    s.acc = {v(rng), -9.81, 0};
    s.rot = randomRotation(rng);
    s.angvel = {0, v(rng) / 4, 0};
    int cell = cellOf(codec, s.pos.x, s.pos.z);
    int largest = -1;
    State once = codec.roundTrip(s, m, cell, &largest);
    State viaFloat = once;
    for (V3* f : {&viaFloat.pos, &viaFloat.vel, &viaFloat.acc, &viaFloat.angvel})
      *f = {double(float(f->x)), double(float(f->y)), double(float(f->z))};
    viaFloat.rot = {float(once.rot.x), float(once.rot.y), float(once.rot.z), float(once.rot.w)};
    BitWriter w;
    WireEntity e;
    e.id = 1;
    e.cell = cell;
    e.model = m;
    e.state = viaFloat;
    e.rot_largest = largest;
    codec.write(w, e, 0, 0);
    BitReader r(w.bytes());
    State twice = codec.read(r, 0, 0)->state;
    ASSERT_EQ(distance(once.pos, twice.pos), 0) << i;
    ASSERT_EQ(distance(once.vel, twice.vel), 0) << i;
    ASSERT_EQ(distance(once.acc, twice.acc), 0) << i;
    ASSERT_EQ(distance(once.angvel, twice.angvel), 0) << i;
    ASSERT_EQ(once.rot.x, twice.rot.x) << i;
    ASSERT_EQ(once.rot.w, twice.rot.w) << i;
  }
}

TEST(StateCodec, PacksIntoBoundedChunksAndUnpacksThemExactly) {
  StateCodec codec(params());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> x(-500, 500), z(-300, 300), v(-3, 3);
  std::vector<WireEntity> in;
  std::uint64_t id = 0;
  for (int i = 0; i < 600; ++i) {
    WireEntity e;
    id += 1 + rng() % 1000;
    e.id = id;
    e.kind = std::uint8_t(i % 5);
    e.tick = 1000 - rng() % 200;
    e.model = {Order(i % 3), Spin(i % 2)};
    e.state.pos = {x(rng), 0.5, z(rng)};
    e.state.vel = {v(rng), 0, v(rng)};
    e.state.rot = randomRotation(rng);
    e.cell = cellOf(codec, e.state.pos.x, e.state.pos.z);
    e.state = codec.roundTrip(e.state, e.model, e.cell);
    in.push_back(e);
  }
  auto chunks = codec.pack(in, 1000, 1200);
  ASSERT_GT(chunks.size(), 1u);
  std::vector<WireEntity> out;
  for (const PackedChunk& c : chunks) {
    EXPECT_LE(c.bytes.size(), 1200u);
    auto got = codec.unpack(c.bytes, c.count, 1000);
    ASSERT_TRUE(got.has_value());
    out.insert(out.end(), got->begin(), got->end());
  }
  ASSERT_EQ(out.size(), in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    EXPECT_EQ(out[i].id, in[i].id);
    EXPECT_EQ(out[i].kind, in[i].kind);
    EXPECT_EQ(out[i].tick, in[i].tick);
    EXPECT_EQ(out[i].model.order, in[i].model.order);
    EXPECT_EQ(out[i].model.spin, in[i].model.spin);
    EXPECT_EQ(distance(out[i].state.pos, in[i].state.pos), 0);
    EXPECT_LT(angleBetween(out[i].state.rot, in[i].state.rot), 1e-12);
  }
  // A walker's update (first order, fixed) costs well under 24 bytes.
  EXPECT_LT(codec.stateBits({Order::First, Spin::Fixed}) + 30, 24 * 8);
}

// The gateway encodes each entity's state once a tick and packs many players' streams from
// those encodings: they must be the very streams packed from the entities, chunk for chunk.
TEST(StateCodec, EncodedStatesPackIntoTheSameStreamsAsTheEntities) {
  StateCodec codec(params());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> x(-500, 500), z(-300, 300), v(-3, 3);
  std::vector<WireEntity> in;
  std::uint64_t id = 0;
  for (int i = 0; i < 400; ++i) {
    WireEntity e;
    id += 1 + rng() % 5000;
    e.id = id;
    e.kind = std::uint8_t(i % 5);
    e.tick = 1000 - rng() % 300;
    e.model = {Order(i % 3), Spin((i / 3) % 2)};
    e.state.pos = {x(rng), 3.25, z(rng)};
    e.state.vel = {v(rng), v(rng), v(rng)};
    e.state.acc = {0, -9.81, v(rng)};
    e.state.rot = randomRotation(rng);
    e.state.angvel = {v(rng), v(rng), v(rng)};
    e.cell = cellOf(codec, e.state.pos.x, e.state.pos.z);
    e.rot_largest = i % 5 == 0 ? int(rng() % 4) : -1;
    in.push_back(e);
  }
  std::vector<EncodedState> states;
  for (const WireEntity& e : in) {
    states.push_back(codec.encodeState(e));
    EXPECT_EQ(states.back().bits, codec.stateBits(e.model));
    // The field groups of a bandwidth profile add up to the record, read back from its bits.
    FieldBits f = codec.fieldBits(states.back());
    EXPECT_EQ(f.total(), states.back().bits);
    EXPECT_EQ(f.velocity > 0, e.model.order != Order::Static);
  }
  std::vector<EncodedEntity> encoded;
  for (std::size_t i = 0; i < in.size(); ++i) encoded.push_back({in[i].id, in[i].tick, &states[i]});
  // One kept chunk list across all sizes, as the gateway keeps it: reused storage must not
  // leak bytes of an earlier, longer stream into a later one.
  std::vector<PackedChunk> got;
  for (std::size_t max_bytes : {std::size_t{40}, std::size_t{1200}, std::size_t{300}}) {
    auto want = codec.pack(in, 1000, max_bytes);
    std::size_t n = codec.packInto(encoded, 1000, max_bytes, got);
    ASSERT_EQ(n, want.size()) << max_bytes;
    for (std::size_t c = 0; c < want.size(); ++c) {
      EXPECT_EQ(got[c].count, want[c].count);
      EXPECT_EQ(got[c].bytes, want[c].bytes) << "chunk " << c << " of " << max_bytes << " B";
    }
  }
  // And the reader, which knows nothing of encoded states, takes them back.
  ASSERT_EQ(codec.packInto(encoded, 1000, 1 << 20, got), 1u);
  auto back = codec.unpack(got[0].bytes, got[0].count, 1000);
  ASSERT_TRUE(back.has_value());
  ASSERT_EQ(back->size(), in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    EXPECT_EQ((*back)[i].id, in[i].id);
    EXPECT_EQ((*back)[i].tick, in[i].tick);
  }
}

TEST(StateCodec, ACodecWhoseRecordsWouldNotFitAnEncodedStateIsRefused) {
  CodecParams p = params();
  p.position_resolution = 1e-9f;
  p.velocity_resolution = p.acceleration_resolution = p.angular_velocity_resolution = 1e-9f;
  p.max_speed = p.max_acceleration = p.max_angular_velocity = 1e9f;
  try {
    StateCodec codec(p);
    FAIL() << "a record of " << codec.stateBits({Order::Second, Spin::Rotating}) << " bits";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("state codec: a record's state takes ", 0), 0u)
        << e.what();
  }
}

TEST(StateCodec, MalformedStreamsAreRefused) {
  StateCodec codec(params());
  WireEntity e;
  e.id = 42;
  e.tick = 90;
  e.state.pos = {10, 1, 10};
  e.cell = cellOf(codec, 10, 10);
  auto chunks = codec.pack(std::span(&e, 1), 100, 1200);
  ASSERT_EQ(chunks.size(), 1u);
  std::vector<std::uint8_t> bytes = chunks[0].bytes;
  EXPECT_TRUE(codec.unpack(bytes, 1, 100).has_value());
  EXPECT_FALSE(codec.unpack(bytes, 2, 100).has_value());  // count lies
  EXPECT_FALSE(codec.unpack(bytes, 1, 5).has_value());    // state from the future
  EXPECT_FALSE(codec.unpack(std::span(bytes).first(bytes.size() - 2), 1, 100).has_value());
  std::vector<std::uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_FALSE(codec.unpack(longer, 1, 100).has_value());  // trailing garbage
  EXPECT_FALSE(codec.unpack(bytes, 1u << 30, 100).has_value());
  // Random bytes never crash and never yield out-of-range cells.
  std::mt19937_64 rng(5);
  int accepted = 0;
  for (int i = 0; i < 20000; ++i) {
    std::vector<std::uint8_t> junk(1 + rng() % 64);
    for (auto& b : junk) b = std::uint8_t(rng());
    auto got = codec.unpack(junk, 1 + rng() % 3, 1'000'000);
    if (!got) continue;
    ++accepted;
    for (const WireEntity& w : *got) {
      EXPECT_LT(w.cell, codec.cellCount());
      EXPECT_NEAR(std::sqrt(w.state.rot.x * w.state.rot.x + w.state.rot.y * w.state.rot.y +
                            w.state.rot.z * w.state.rot.z + w.state.rot.w * w.state.rot.w),
                  1, 1e-9);
    }
  }
  EXPECT_LT(accepted, 20000);
}

}  // namespace
}  // namespace zonesim::dr
