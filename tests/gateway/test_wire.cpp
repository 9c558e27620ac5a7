// The wire checks against crafted bytes, and chunking limits.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/rng.h"
#include "gateway/wire_encode.h"
#include "gateway/wire_verify.h"

namespace zonesim::gateway {
namespace {

DropReason reasonOf(const Bytes& b, Direction d = Direction::ToGateway) {
  Verified v = verifyDatagram(b, d);
  EXPECT_FALSE(v.ok());
  return v.reason;
}

proto::EntityState state(std::uint64_t id, float x) {
  return proto::EntityState(id, 0, proto::Vec3f(x, 0, -x), proto::Vec3f(1, 0, 2),
                            proto::Quatf(0, 0, 0, 1));
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
  DropReason r = reasonOf(garbage);
  EXPECT_TRUE(r == DropReason::BadIdentifier || r == DropReason::Malformed);
  // Garbage that happens to carry the identifier still fails the Verifier.
  garbage[4] = 'Z', garbage[5] = 'S', garbage[6] = 'C', garbage[7] = 'P';
  EXPECT_EQ(reasonOf(garbage), DropReason::Malformed);
}

TEST(Wire, TruncatedBuffers) {
  Bytes hello = encodeHello(7, "a somewhat longer player name");
  EXPECT_EQ(reasonOf(Bytes(hello.begin(), hello.begin() + 5)), DropReason::Truncated);
  EXPECT_EQ(reasonOf(Bytes{}), DropReason::Truncated);
  Bytes half(hello.begin(), hello.begin() + long(hello.size() / 2));
  EXPECT_EQ(reasonOf(half), DropReason::Malformed);
}

TEST(Wire, WrongFileIdentifier) {
  Bytes b = encodeHello(7, "p");
  b[4] = 'X';
  EXPECT_EQ(reasonOf(b), DropReason::BadIdentifier);
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
  EXPECT_EQ(reasonOf(b), DropReason::NoMessage);
}

TEST(Wire, NonFiniteStatesRejectedAtTheClient) {
  std::vector<proto::EntityState> s{state(1, 1)};
  s.push_back(proto::EntityState(2, 0, proto::Vec3f(std::nanf(""), 0, 0), proto::Vec3f(0, 0, 0),
                                 proto::Quatf(0, 0, 0, 1)));
  auto chunks = encodeStateChunks(3, 1, s);
  ASSERT_EQ(chunks.size(), 1u);
  EXPECT_EQ(reasonOf(chunks[0], Direction::ToClient), DropReason::OutOfRange);
}

TEST(Wire, ChunksStayWithinLimitAndLoseNothing) {
  for (std::size_t n : {0u, 1u, 22u, 23u, 100u, 1000u}) {
    std::vector<proto::EntityState> states;
    for (std::size_t i = 0; i < n; ++i) states.push_back(state(i + 1, float(i)));
    for (bool spawn : {false, true}) {
      auto chunks = spawn ? encodeSpawnChunks(5, 9, states) : encodeStateChunks(5, 9, states);
      EXPECT_EQ(chunks.size(), (n + kStatesPerDatagram - 1) / kStatesPerDatagram);
      std::vector<std::uint64_t> seen;
      for (const Bytes& c : chunks) {
        EXPECT_LE(c.size(), kMaxDatagramBytes);
        Verified v = verifyDatagram(c, Direction::ToClient);
        ASSERT_TRUE(v.ok()) << dropReasonName(v.reason);
        auto* list = spawn ? v.datagram->msg_as_Spawn()->entities()
                           : v.datagram->msg_as_StateBatch()->updates();
        for (const proto::EntityState* s : *list) {
          EXPECT_EQ(s->pos().x(), float(s->id() - 1));
          seen.push_back(s->id());
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
  std::vector<proto::EntityState> states;
  for (std::uint64_t i = 1; i <= 20; ++i) states.push_back(state(i, float(i)));
  WelcomeInfo w;
  w.token = 3;
  w.world_max = proto::Vec3f(1, 1, 1);
  std::vector<Bytes> seeds{encodeStateChunks(3, 1, states)[0], encodeSpawnChunks(3, 1, states)[0],
                           encodeWelcome(w), encodeHandoff(3, {1, 0, 1, 2, 3})};
  Pcg32 rng(77, 3);
  int passed = 0;
  for (int i = 0; i < 20000; ++i) {
    Bytes b = seeds[rng.next() % seeds.size()];
    for (int f = 0; f < 3; ++f) b[rng.next() % b.size()] = std::uint8_t(rng.next());
    Verified v = verifyDatagram(b, Direction::ToClient);
    if (!v.ok()) continue;
    ++passed;
    if (v.datagram->msg_type() != proto::Message::StateBatch) continue;
    for (const proto::EntityState* s : *v.datagram->msg_as_StateBatch()->updates()) {
      EXPECT_TRUE(validEntityState(*s));
    }
  }
  EXPECT_GT(passed, 0) << "some corruptions only touch values that stay in range";
}

}  // namespace
}  // namespace zonesim::gateway
