// The lean downlink frame: its layout byte by byte, the keyed checksum (a wrong token fails),
// truncation, extension, bit flips, count lies, malformed numbers.
#include "wire/downlink_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string_view>

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

}  // namespace
}  // namespace zonesim::gateway
