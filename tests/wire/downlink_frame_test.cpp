// The lean downlink frame: its layout byte by byte, round trips of every kind, the keyed
// checksum (a wrong token fails), truncation, extension, bit flips, count lies, malformed
// numbers, and that a FlatBuffers datagram is never taken for a frame nor a frame for one.
#include "wire/downlink_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string_view>

#include "common/rng.h"
#include "wire/datagram_checksum.h"
#include "wire/leb128.h"
#include "wire/wire_encode.h"
#include "wire_states.h"

namespace zonesim::gateway {
namespace {

using testing::codec;
using testing::state;

constexpr std::uint64_t kToken = 0x1122334455667788ULL;

std::vector<std::uint8_t> tokenBytes(std::uint64_t token) {
  std::vector<std::uint8_t> key;
  for (int i = 0; i < 8; ++i) key.push_back(std::uint8_t(token >> (8 * i)));
  return key;
}

// A frame body (no trailer) sealed with the keyed checksum, so the checks behind it see it.
Bytes sealedFor(std::uint64_t token, Bytes body) {
  std::uint32_t crc = crc32c(tokenBytes(token), body);
  for (int i = 0; i < 4; ++i) body.push_back(std::uint8_t(crc >> (8 * i)));
  return body;
}

DropReason dropOf(const Bytes& b, std::uint64_t token = kToken) {
  ParsedFrame p = parseFrame(b, token);
  EXPECT_FALSE(p.ok());
  return p.drop.value_or(DropReason::Count);
}

std::vector<dr::WireEntity> states(std::size_t n) {
  std::vector<dr::WireEntity> v;
  for (std::size_t i = 0; i < n; ++i) v.push_back(state(i + 1, float(i % 1000)));
  return v;
}

// n states packed for a batch of tick 9, as one frame payload.
Bytes packed(std::size_t n) {
  return codec().pack(states(n), 9, kMaxFramePayloadBytes)[0].bytes;
}

TEST(DownlinkFrame, KeyedChecksumIsTheChecksumOfKeyAndBytesAsOneBuffer) {
  auto bytes = [](std::string_view s) { return std::vector<std::uint8_t>(s.begin(), s.end()); };
  EXPECT_EQ(crc32c(bytes("123456789")), 0xE3069283u);  // the CRC-32C check value
  EXPECT_EQ(crc32c(bytes("1234"), bytes("56789")), 0xE3069283u);
}

TEST(DownlinkFrame, LayoutIsTagSeqTickCountPayloadAndKeyedTrailer) {
  Bytes payload{0xAA, 0xBB, 0xCC, 0xDD, 0xEE};
  Bytes f = encodeFrame({FrameKind::Spawn, 0x01020304, 300, 2}, payload, kToken);
  Bytes body{0xA2, 0x04, 0x03, 0x02, 0x01, 0xAC, 0x02, 0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE};
  ASSERT_EQ(f.size(), body.size() + 4);
  EXPECT_EQ(Bytes(f.begin(), f.end() - 4), body);
  Bytes keyed = tokenBytes(kToken);
  keyed.insert(keyed.end(), body.begin(), body.end());
  std::uint32_t crc = crc32c(keyed);
  EXPECT_EQ(Bytes(f.end() - 4, f.end()), (Bytes{std::uint8_t(crc), std::uint8_t(crc >> 8),
                                                std::uint8_t(crc >> 16), std::uint8_t(crc >> 24)}));
}

TEST(DownlinkFrame, OnlyTheSessionsTokenChecks) {
  Bytes f = encodeFrame({FrameKind::StateBatch, 3, 9, 3}, packed(3), kToken);
  ASSERT_TRUE(parseFrame(f, kToken).ok());
  EXPECT_EQ(dropOf(f, 0), DropReason::NotReady) << "no Welcome yet";
  EXPECT_EQ(dropOf(f, kToken + 1), DropReason::BadChecksum);
  for (int bit = 0; bit < 64; ++bit)
    EXPECT_EQ(dropOf(f, kToken ^ (std::uint64_t{1} << bit)), DropReason::BadChecksum) << bit;
  // The token is nowhere in the frame: it is only the checksum's key.
  Bytes key = tokenBytes(kToken);
  EXPECT_EQ(std::search(f.begin(), f.end(), key.begin(), key.end()), f.end());
}

TEST(DownlinkFrame, TruncationExtensionAndEveryBitFlipFail) {
  for (Bytes f : {encodeFrame({FrameKind::Spawn, 7, 5000, 4}, packed(4), kToken),
                  encodeFrame({FrameKind::Despawn, 8, 5000, 3}, Bytes{7, 2, 21}, kToken),
                  encodeFrame({FrameKind::StateBatch, 0, 5000, 0}, {}, kToken)}) {
    ASSERT_TRUE(parseFrame(f, kToken).ok());
    for (std::size_t n = 0; n < f.size(); ++n) {
      DropReason r = dropOf(Bytes(f.begin(), f.begin() + long(n)));
      EXPECT_TRUE(r == DropReason::Truncated || r == DropReason::BadChecksum) << n;
    }
    Bytes longer = f;
    longer.push_back(0);
    EXPECT_EQ(dropOf(longer), DropReason::BadChecksum);
    for (std::size_t i = 0; i < f.size(); ++i)
      for (int bit = 0; bit < 8; ++bit) {
        Bytes flipped = f;
        flipped[i] ^= std::uint8_t(1u << bit);
        DropReason r = dropOf(flipped);
        // A flipped tag bit may name no kind; every other flip fails the checksum.
        EXPECT_TRUE(r == DropReason::BadChecksum || (i == 0 && r == DropReason::BadIdentifier))
            << i << ":" << bit;
      }
  }
  Bytes big(kMaxDatagramBytes + 1, 0xA1);
  EXPECT_EQ(dropOf(big), DropReason::TooLarge);
}

TEST(DownlinkFrame, CountsThePayloadCannotHoldAreOutOfRange) {
  auto frame = [](FrameKind k, std::size_t count, Bytes payload) {
    return encodeFrame({k, 1, 9, count}, payload, kToken);
  };
  // 3 bytes hold one 20-bit record at most.
  EXPECT_EQ(dropOf(frame(FrameKind::StateBatch, 2, {1, 2, 3})), DropReason::OutOfRange);
  EXPECT_EQ(dropOf(frame(FrameKind::Spawn, 5, {1, 2, 3})), DropReason::OutOfRange);
  EXPECT_TRUE(parseFrame(frame(FrameKind::Spawn, 1, {1, 2, 3}), kToken).ok())
      << "plausible: the codec checks the record";
  EXPECT_FALSE(codec().unpack(Bytes{1, 2, 3}, 1, 9).has_value());
  // Only a StateBatch may be empty, and only with nothing packed.
  EXPECT_EQ(dropOf(frame(FrameKind::StateBatch, 0, {1})), DropReason::OutOfRange);
  EXPECT_EQ(dropOf(frame(FrameKind::Spawn, 0, {})), DropReason::OutOfRange);
  EXPECT_EQ(dropOf(frame(FrameKind::Despawn, 0, {})), DropReason::OutOfRange);
  // Despawn: count ids, each a delta of at least 1, filling the payload exactly.
  EXPECT_EQ(dropOf(frame(FrameKind::Despawn, 3, {5, 1})), DropReason::OutOfRange);
  EXPECT_EQ(dropOf(frame(FrameKind::Despawn, 2, {5, 1, 1})), DropReason::OutOfRange);
  EXPECT_EQ(dropOf(frame(FrameKind::Despawn, 2, {5, 0})), DropReason::OutOfRange);
  EXPECT_EQ(dropOf(frame(FrameKind::Despawn, 1, {0x80})), DropReason::OutOfRange);
  Bytes wraps;
  appendLeb128(wraps, ~std::uint64_t{0});
  appendLeb128(wraps, 1);
  EXPECT_EQ(dropOf(frame(FrameKind::Despawn, 2, wraps)), DropReason::OutOfRange);
  ParsedFrame ok = parseFrame(frame(FrameKind::Despawn, 2, {5, 1}), kToken);
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(ok.frame.ids, (std::vector<std::uint64_t>{5, 6}));
}

TEST(DownlinkFrame, MalformedNumbersAndUnknownTagsAreDropped) {
  Bytes head{0xA1, 1, 0, 0, 0};
  auto with = [&](Bytes rest) {
    Bytes b = head;
    b.insert(b.end(), rest.begin(), rest.end());
    return sealedFor(kToken, b);
  };
  EXPECT_EQ(dropOf(with({0x80, 0x80, 0x80, 0x80})), DropReason::Malformed) << "tick runs off";
  EXPECT_EQ(dropOf(with({0x85, 0x00, 0x00})), DropReason::Malformed) << "a padded tick";
  EXPECT_EQ(dropOf(with({0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x02, 0x00})),
            DropReason::Malformed)
      << "a tick over 64 bits";
  EXPECT_EQ(dropOf(with({0x09, 0x80, 0x80, 0x01})), DropReason::Malformed) << "a 3-byte count";
  EXPECT_TRUE(parseFrame(with({0x09, 0x00}), kToken).ok()) << "the clock tick, by hand";
  for (std::uint8_t tag : {0xA0, 0xA4, 0xAF, 0xB1, 0x81}) {
    Bytes b = with({0x09, 0x00});
    b[0] = tag;
    EXPECT_EQ(dropOf(sealedFor(kToken, Bytes(b.begin(), b.end() - 4))), DropReason::BadIdentifier)
        << int(tag);
  }
  EXPECT_THROW(encodeFrame({FrameKind::Despawn, 1, 9, kMaxFrameCount + 1}, {}, kToken),
               std::invalid_argument);
  EXPECT_THROW(encodeFrame({FrameKind::Spawn, 1, 9, 1}, Bytes(kMaxDatagramBytes - 10), 1),
               std::invalid_argument);
  Bytes ids;
  EXPECT_THROW(appendDespawnId(ids, 5, 5, 100), std::invalid_argument) << "ids ascend";
  EXPECT_FALSE(appendDespawnId(ids, 0, 1ULL << 40, 5)) << "a 6-byte delta past 5 bytes";
  EXPECT_TRUE(ids.empty());
}

// The encoders the gateway calls (wire/wire_encode.h), which frame what they chunk.

TEST(DownlinkFrame, FramingIsThirteenBytesForAServerUpAnHour) {
  // 108,000 ticks (an hour at 30 Hz) take 3 LEB128 bytes: tag 1 + seq 4 + 3 + count 1 + CRC 4.
  std::vector<dr::WireEntity> one = states(1);
  one[0].tick = 108'000;
  auto packed = codec().pack(one, 108'000, kPackedBytesPerDatagram);
  Bytes f = encodeStateChunks(kToken, 108'000, codec(), one)[0];
  EXPECT_EQ(f.size() - packed[0].bytes.size(), 13u);
  EXPECT_EQ(encodeClockTick(kToken, 108'000).size(), 13u);
}

TEST(DownlinkFrame, EveryKindRoundTrips) {
  std::vector<dr::WireEntity> v = states(30);
  ChunkSeq numbered{[](void* n) { return ++*static_cast<std::uint32_t*>(n); }, nullptr, nullptr};
  std::uint32_t next = 40;
  numbered.ctx = &next;
  for (bool spawn : {false, true}) {
    Bytes f = spawn ? encodeSpawnChunks(kToken, 9, codec(), v, numbered)[0]
                    : encodeStateChunks(kToken, 9, codec(), v, numbered)[0];
    ParsedFrame p = parseFrame(f, kToken);
    ASSERT_TRUE(p.ok()) << dropReasonName(*p.drop);
    EXPECT_EQ(p.frame.header.kind, spawn ? FrameKind::Spawn : FrameKind::StateBatch);
    EXPECT_EQ(p.frame.header.seq, spawn ? 42u : 41u);
    EXPECT_EQ(p.frame.header.tick, 9u);
    ASSERT_EQ(p.frame.header.count, v.size());
    auto got = codec().unpack(p.frame.payload, p.frame.header.count, p.frame.header.tick);
    ASSERT_TRUE(got.has_value());
    for (std::size_t i = 0; i < v.size(); ++i) {
      EXPECT_EQ((*got)[i].id, v[i].id);
      EXPECT_EQ((*got)[i].state.pos.x, v[i].state.pos.x);
      EXPECT_EQ((*got)[i].state.vel.z, v[i].state.vel.z);
    }
  }
  std::vector<std::uint64_t> ids{3, 4, 1000, 0x0001000000000005ULL, ~std::uint64_t{0}};
  ParsedFrame d = parseFrame(encodeDespawnChunks(kToken, 1ULL << 40, ids, numbered)[0], kToken);
  ASSERT_TRUE(d.ok()) << dropReasonName(*d.drop);
  EXPECT_EQ(d.frame.header.kind, FrameKind::Despawn);
  EXPECT_EQ(d.frame.header.seq, 43u);
  EXPECT_EQ(d.frame.header.tick, 1ULL << 40);
  EXPECT_EQ(d.frame.ids, ids);
  EXPECT_THROW(encodeDespawnChunks(kToken, 9, std::vector<std::uint64_t>{5, 5}),
               std::invalid_argument);
  EXPECT_THROW(encodeDespawnChunks(kToken, 9, std::vector<std::uint64_t>{0}),
               std::invalid_argument);
  Bytes clock = encodeClockTick(kToken, ~std::uint64_t{0});
  ParsedFrame c = parseFrame(clock, kToken);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c.frame.header.kind, FrameKind::StateBatch);
  EXPECT_EQ(c.frame.header.seq, 0u) << "a clock tick is unnumbered";
  EXPECT_EQ(c.frame.header.tick, ~std::uint64_t{0});
  EXPECT_EQ(c.frame.header.count, 0u);
  EXPECT_TRUE(c.frame.payload.empty());
}

TEST(DownlinkFrame, NeitherFormatIsTakenForTheOther) {
  WelcomeInfo w;
  w.token = kToken;
  w.world_max = proto::Vec3f(1, 1, 1);
  std::vector<Bytes> flat{encodeHello(7, "p"),
                          encodeInput(kToken, 1, 0.5f, 0),
                          encodePing(kToken, 1),
                          encodeBye(kToken),
                          encodeWelcome(w),
                          encodePong(kToken, 1, 2),
                          encodeHandoff(kToken, {1, 0, 1, 2, 3, 4})};
  for (const Bytes& b : flat) {
    EXPECT_LT(b[0], 0x80);
    EXPECT_FALSE(isDownlinkFrame(b));
    EXPECT_EQ(dropOf(b), DropReason::BadIdentifier);
  }
  std::vector<Bytes> frames{encodeStateChunks(kToken, 9, codec(), states(3))[0],
                            encodeSpawnChunks(kToken, 9, codec(), states(3))[0],
                            encodeDespawnChunks(kToken, 9, std::vector<std::uint64_t>{1, 2})[0],
                            encodeClockTick(kToken, 9)};
  for (const Bytes& f : frames) {
    EXPECT_TRUE(isDownlinkFrame(f));
    for (Direction d : {Direction::ToClient, Direction::ToGateway}) {
      EXPECT_FALSE(verifyDatagram(f, d).ok());
      // Even with the plain trailer a FlatBuffers datagram has, it is not one.
      Bytes plain(f.begin(), f.end() - 4);
      appendChecksum(plain);
      EXPECT_FALSE(verifyDatagram(plain, d).ok());
    }
  }
}

TEST(DownlinkFrame, ChunksStayWithinLimitAndLoseNothing) {
  for (std::size_t n : {0u, 1u, 60u, 61u, 100u, 1000u}) {
    std::vector<dr::WireEntity> v = states(n);
    for (bool spawn : {false, true}) {
      auto chunks =
          spawn ? encodeSpawnChunks(5, 9, codec(), v) : encodeStateChunks(5, 9, codec(), v);
      EXPECT_EQ(chunks.empty(), n == 0);
      std::vector<std::uint64_t> seen;
      for (const Bytes& c : chunks) {
        EXPECT_LE(c.size(), kMaxDatagramBytes);
        ParsedFrame p = parseFrame(c, 5);
        ASSERT_TRUE(p.ok()) << dropReasonName(*p.drop);
        auto got = codec().unpack(p.frame.payload, p.frame.header.count, 9);
        ASSERT_TRUE(got.has_value());
        for (const dr::WireEntity& s : *got) {
          EXPECT_EQ(s.state.pos.x, v[s.id - 1].state.pos.x);
          seen.push_back(s.id);
        }
      }
      ASSERT_EQ(seen.size(), n);
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], i + 1);
    }
  }
}

TEST(DownlinkFrame, DespawnChunksStayWithinLimitAndLoseNothing) {
  // Far-apart ids: 6-byte deltas, a few hundred to a frame.
  std::vector<std::uint64_t> ids;
  for (std::uint64_t i = 1; i <= 1000; ++i) ids.push_back(i * 0x1000000001ULL);
  std::vector<std::size_t> counts;
  ChunkSeq seq{nullptr, nullptr, &counts};
  auto chunks = encodeDespawnChunks(5, 9, ids, seq);
  ASSERT_GT(chunks.size(), 1u);
  std::vector<std::uint64_t> seen;
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    EXPECT_LE(chunks[i].size(), kMaxDatagramBytes);
    ParsedFrame p = parseFrame(chunks[i], 5);
    ASSERT_TRUE(p.ok()) << dropReasonName(*p.drop);
    EXPECT_EQ(p.frame.ids.size(), counts[i]) << "what the resend tracker is told";
    seen.insert(seen.end(), p.frame.ids.begin(), p.frame.ids.end());
  }
  EXPECT_EQ(seen, ids);
  // Filled to within one id (6 bytes) before the next frame starts.
  EXPECT_GT(chunks.front().size(), kMaxFramePayloadBytes);
  // Neighbouring ids cost a byte each.
  std::vector<std::uint64_t> near;
  for (std::uint64_t i = 1; i <= 100; ++i) near.push_back((std::uint64_t{3} << 48) + i);
  EXPECT_EQ(encodeDespawnChunks(5, 9, near)[0].size(), 1 + 4 + 1 + 1 + 8 + 99 + 4u);
}

// Corrupted frames re-sealed with the right key (what only a broken gateway could send): the
// parser and the codec never read out of bounds, and whatever passes holds in-range states.
TEST(DownlinkFrame, CorruptedFramesNeverPassBadStates) {
  std::vector<Bytes> seeds{encodeStateChunks(kToken, 9, codec(), states(20))[0],
                           encodeSpawnChunks(kToken, 9, codec(), states(20))[0],
                           encodeDespawnChunks(kToken, 9, std::vector<std::uint64_t>{4, 8, 9})[0]};
  Pcg32 rng(77, 3);
  int passed = 0, unpacked = 0;
  for (int i = 0; i < 20000; ++i) {
    const Bytes& seed = seeds[rng.next() % seeds.size()];
    Bytes b(seed.begin(), seed.end() - 4);
    for (std::uint32_t f = 0, n = 1 + rng.next() % 3; f < n; ++f)
      b[rng.next() % b.size()] = std::uint8_t(rng.next());
    if (rng.next() % 4 == 0) b.resize(rng.next() % (b.size() + 1));
    Bytes frame = sealedFor(kToken, b);  // the parsed payload aliases it
    ParsedFrame p = parseFrame(frame, kToken);
    if (!p.ok()) continue;
    ++passed;
    if (p.frame.header.kind == FrameKind::Despawn) {
      EXPECT_TRUE(std::is_sorted(p.frame.ids.begin(), p.frame.ids.end()));
      EXPECT_EQ(p.frame.ids.size(), p.frame.header.count);
      continue;
    }
    auto got = codec().unpack(p.frame.payload, p.frame.header.count, p.frame.header.tick);
    if (!got) continue;  // the client drops it as out of range
    ++unpacked;
    for (const dr::WireEntity& s : *got) {
      EXPECT_LT(s.cell, codec().cellCount());
      EXPECT_TRUE(std::isfinite(s.state.pos.x) && std::isfinite(s.state.vel.z));
      EXPECT_LE(s.tick, p.frame.header.tick);
    }
  }
  EXPECT_GT(passed, 0) << "some corruptions only touch values that stay in range";
  EXPECT_GT(unpacked, 0);
}

}  // namespace
}  // namespace zonesim::gateway
