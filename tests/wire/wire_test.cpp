// The wire checks against crafted bytes, and chunking limits.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/rng.h"
#include "wire/datagram_checksum.h"
#include "wire/wire_encode.h"
#include "wire/wire_verify.h"

namespace zonesim::gateway {
namespace {

// A datagram body (no trailer) with its checksum appended, so the checks behind it see it.
Bytes sealed(Bytes body) {
  appendChecksum(body);
  return body;
}
// The body of an encoded datagram, without its checksum.
Bytes bodyOf(const Bytes& b) {
  return Bytes(b.begin(), b.end() - long(kChecksumBytes));
}

DropReason reasonOf(const Bytes& b, Direction d = Direction::ToGateway) {
  Verified v = verifyDatagram(b, d);
  EXPECT_FALSE(v.ok());
  return v.reason;
}

const dr::StateCodec& codec() {
  static const dr::StateCodec c{dr::CodecParams{}};
  return c;
}

// An entity at (x, 0, 1000 - x) in the default codec's 1000 m world, first order.
dr::WireEntity state(std::uint64_t id, float x) {
  dr::WireEntity e;
  e.id = id;
  e.tick = 9;
  e.state.pos = {x, 0, 1000 - x};
  e.state.vel = {1, 0, 2};
  e.cell = codec().columns() * int((1000 - x) / 50 < 19 ? (1000 - x) / 50 : 19) +
           int(x / 50 < 19 ? x / 50 : 19);
  e.state = codec().roundTrip(e.state, e.model, e.cell);
  return e;
}

Bytes batchOf(std::uint16_t count, std::vector<std::uint8_t> packed) {
  flatbuffers::FlatBufferBuilder fbb;
  auto v = fbb.CreateVector(packed);
  proto::FinishDatagramBuffer(
      fbb, proto::CreateDatagram(fbb, 3, proto::Message::StateBatch,
                                 proto::CreateStateBatch(fbb, 1, count, v).Union()));
  return sealed(Bytes(fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize()));
}

TEST(Wire, ValidHelloAndInputPass) {
  EXPECT_TRUE(verifyDatagram(encodeHello(7, "p"), Direction::ToGateway).ok());
  EXPECT_TRUE(verifyDatagram(encodeInput(9, 1, 0.6f, 0.8f), Direction::ToGateway).ok());
  EXPECT_TRUE(verifyDatagram(encodePing(9, 1), Direction::ToGateway).ok());
  EXPECT_TRUE(verifyDatagram(encodeBye(9), Direction::ToGateway).ok());
}

TEST(Wire, GarbageIsMalformedOrBadIdentifier) {
  Bytes garbage(64);
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = std::uint8_t(i * 37 + 11);
  EXPECT_EQ(reasonOf(garbage), DropReason::BadChecksum);
  DropReason r = reasonOf(sealed(garbage));
  EXPECT_TRUE(r == DropReason::BadIdentifier || r == DropReason::Malformed);
  // Garbage that happens to carry the identifier still fails the Verifier.
  garbage[4] = 'Z', garbage[5] = 'S', garbage[6] = 'C', garbage[7] = 'P';
  EXPECT_EQ(reasonOf(sealed(garbage)), DropReason::Malformed);
}

TEST(Wire, TruncatedBuffers) {
  Bytes hello = encodeHello(7, "a somewhat longer player name");
  EXPECT_EQ(reasonOf(Bytes(hello.begin(), hello.begin() + 5)), DropReason::Truncated);
  EXPECT_EQ(reasonOf(Bytes{}), DropReason::Truncated);
  Bytes half(hello.begin(), hello.begin() + long(hello.size() / 2));
  EXPECT_EQ(reasonOf(half), DropReason::BadChecksum);
  EXPECT_EQ(reasonOf(sealed(half)), DropReason::Malformed);
}

TEST(Wire, WrongFileIdentifier) {
  Bytes b = bodyOf(encodeHello(7, "p"));
  b[4] = 'X';
  EXPECT_EQ(reasonOf(sealed(b)), DropReason::BadIdentifier);
}

TEST(Wire, OversizeDatagram) {
  Bytes b = encodeHello(7, "p");
  b.resize(kMaxDatagramBytes + 1);
  EXPECT_EQ(reasonOf(b), DropReason::TooLarge);
}

TEST(Wire, OutOfRangeValues) {
  EXPECT_EQ(reasonOf(encodeInput(9, 1, 1.0f, 1.0f)), DropReason::OutOfRange);
  float nan = std::numeric_limits<float>::quiet_NaN();
  float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(reasonOf(encodeInput(9, 1, nan, 0)), DropReason::OutOfRange);
  EXPECT_EQ(reasonOf(encodeInput(9, 1, 0, inf)), DropReason::OutOfRange);
  EXPECT_EQ(reasonOf(encodeInput(9, 0, 0, 0)), DropReason::OutOfRange);  // seq starts at 1
  EXPECT_EQ(reasonOf(encodeHello(0, "p")), DropReason::OutOfRange);
  EXPECT_EQ(reasonOf(encodeHello(1, std::string(kMaxNameBytes + 1, 'n'))), DropReason::OutOfRange);
}

TEST(Wire, DirectionDecidesWhichMessagesAreAccepted) {
  EXPECT_EQ(reasonOf(encodePong(1, 2, 3)), DropReason::UnexpectedType);
  EXPECT_EQ(reasonOf(encodeHello(1, "p"), Direction::ToClient), DropReason::UnexpectedType);
  EXPECT_TRUE(verifyDatagram(encodePong(1, 2, 3), Direction::ToClient).ok());
}

TEST(Wire, EmptyUnionIsNoMessage) {
  flatbuffers::FlatBufferBuilder fbb;
  proto::FinishDatagramBuffer(fbb, proto::CreateDatagram(fbb, 5));
  Bytes b(fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize());
  EXPECT_EQ(reasonOf(sealed(b)), DropReason::NoMessage);
}

TEST(Wire, PackedCountsTheBytesCannotHoldAreRejectedAtTheClient) {
  EXPECT_EQ(reasonOf(batchOf(5, {1, 2, 3}), Direction::ToClient), DropReason::OutOfRange);
  EXPECT_EQ(reasonOf(batchOf(0, {1, 2, 3}), Direction::ToClient), DropReason::OutOfRange);
  EXPECT_TRUE(verifyDatagram(batchOf(1, {1, 2, 3}), Direction::ToClient).ok());
}

TEST(Wire, WelcomeWithAnUnusableCodecIsRejected) {
  WelcomeInfo w;
  w.token = 3;
  w.world_max = proto::Vec3f(1, 1, 1);
  EXPECT_TRUE(verifyDatagram(encodeWelcome(w), Direction::ToClient).ok());
  w.codec.cell_size = 0;
  EXPECT_EQ(reasonOf(encodeWelcome(w), Direction::ToClient), DropReason::OutOfRange);
  w.codec = {};
  w.codec.rotation_bits = 40;
  EXPECT_EQ(reasonOf(encodeWelcome(w), Direction::ToClient), DropReason::OutOfRange);
  w.codec = {};
  w.codec.position_resolution = std::nanf("");
  EXPECT_EQ(reasonOf(encodeWelcome(w), Direction::ToClient), DropReason::OutOfRange);
  w.codec = {};
  w.sim_dt = 0;
  EXPECT_EQ(reasonOf(encodeWelcome(w), Direction::ToClient), DropReason::OutOfRange);
}

TEST(Wire, ChunksStayWithinLimitAndLoseNothing) {
  for (std::size_t n : {0u, 1u, 22u, 23u, 100u, 1000u}) {
    std::vector<dr::WireEntity> states;
    for (std::size_t i = 0; i < n; ++i) states.push_back(state(i + 1, float(i % 1000)));
    for (bool spawn : {false, true}) {
      auto chunks = spawn ? encodeSpawnChunks(5, 9, codec(), states)
                          : encodeStateChunks(5, 9, codec(), states);
      EXPECT_EQ(chunks.empty(), n == 0);
      std::vector<std::uint64_t> seen;
      for (const Bytes& c : chunks) {
        EXPECT_LE(c.size(), kMaxDatagramBytes);
        Verified v = verifyDatagram(c, Direction::ToClient);
        ASSERT_TRUE(v.ok()) << dropReasonName(v.reason);
        std::uint16_t count =
            spawn ? v.datagram->msg_as_Spawn()->count() : v.datagram->msg_as_StateBatch()->count();
        auto* bytes = spawn ? v.datagram->msg_as_Spawn()->packed()
                            : v.datagram->msg_as_StateBatch()->packed();
        auto got = codec().unpack(std::span(bytes->data(), bytes->size()), count, 9);
        ASSERT_TRUE(got.has_value());
        for (const dr::WireEntity& s : *got) {
          EXPECT_EQ(s.state.pos.x, states[s.id - 1].state.pos.x);
          seen.push_back(s.id);
        }
      }
      ASSERT_EQ(seen.size(), n);
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], i + 1);
    }
  }
}

TEST(Wire, DespawnChunksStayWithinLimitAndLoseNothing) {
  std::vector<std::uint64_t> ids;
  for (std::uint64_t i = 1; i <= 1000; ++i) ids.push_back(i * 0x1000000001ULL);
  auto chunks = encodeDespawnChunks(5, 9, ids);
  std::vector<std::uint64_t> seen;
  for (const Bytes& c : chunks) {
    EXPECT_LE(c.size(), kMaxDatagramBytes);
    Verified v = verifyDatagram(c, Direction::ToClient);
    ASSERT_TRUE(v.ok());
    for (std::uint64_t id : *v.datagram->msg_as_Despawn()->ids()) seen.push_back(id);
  }
  EXPECT_EQ(seen, ids);
  EXPECT_GT(chunks.front().size(), kMaxDatagramBytes - kChunkOverheadBytes);
}

// Corrupted gateway-to-client datagrams: the client-side check never reads out of bounds and
// whatever passes it holds only finite, in-range states.
TEST(Wire, CorruptedClientBoundDatagramsNeverPassBadStates) {
  std::vector<dr::WireEntity> states;
  for (std::uint64_t i = 1; i <= 20; ++i) states.push_back(state(i, float(i)));
  WelcomeInfo w;
  w.token = 3;
  w.world_max = proto::Vec3f(1, 1, 1);
  std::vector<Bytes> seeds{encodeStateChunks(3, 9, codec(), states)[0],
                           encodeSpawnChunks(3, 9, codec(), states)[0], encodeWelcome(w),
                           encodeHandoff(3, {1, 0, 1, 2, 3})};
  Pcg32 rng(77, 3);
  int passed = 0;
  for (int i = 0; i < 20000; ++i) {
    Bytes b = bodyOf(seeds[rng.next() % seeds.size()]);
    for (int f = 0; f < 3; ++f) b[rng.next() % b.size()] = std::uint8_t(rng.next());
    b = sealed(b);
    Verified v = verifyDatagram(b, Direction::ToClient);
    if (!v.ok()) continue;
    ++passed;
    if (v.datagram->msg_type() != proto::Message::StateBatch) continue;
    const proto::StateBatch* m = v.datagram->msg_as_StateBatch();
    auto got = codec().unpack(std::span(m->packed()->data(), m->packed()->size()), m->count(),
                              m->server_tick());
    if (!got) continue;  // the client drops it as out of range
    for (const dr::WireEntity& s : *got) {
      EXPECT_LT(s.cell, codec().cellCount());
      EXPECT_TRUE(std::isfinite(s.state.pos.x) && std::isfinite(s.state.vel.z));
      EXPECT_LE(s.tick, m->server_tick());
    }
  }
  EXPECT_GT(passed, 0) << "some corruptions only touch values that stay in range";
}

}  // namespace
}  // namespace zonesim::gateway
