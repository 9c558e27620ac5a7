#include "wire/downlink_frame.h"

#include <stdexcept>

#include "wire/datagram_checksum.h"
#include "wire/leb128.h"

namespace zonesim::gateway {

namespace {

constexpr std::size_t kSeqAt = 1, kSeqBytes = 4, kMaxCountBytes = 2;

// The checksum's key: the token's 8 bytes, little-endian.
std::uint32_t keyedCrc(std::uint64_t token, std::span<const std::uint8_t> frame) {
  std::uint8_t key[8];
  for (int i = 0; i < 8; ++i) key[i] = std::uint8_t(token >> (8 * i));
  return crc32c(key, frame);
}

bool knownKind(std::uint8_t tag) {
  return tag == (kFrameTag | std::uint8_t(FrameKind::StateBatch)) ||
         tag == (kFrameTag | std::uint8_t(FrameKind::Spawn)) ||
         tag == (kFrameTag | std::uint8_t(FrameKind::Despawn));
}

// The count against the payload: records take 20 bits at least, ids a byte. Only a StateBatch
// may be empty (the clock tick), and only with nothing packed.
bool plausibleCount(const FrameHeader& h, std::size_t payload_bytes) {
  if (h.count == 0) return h.kind == FrameKind::StateBatch && payload_bytes == 0;
  if (h.kind == FrameKind::Despawn) return h.count <= payload_bytes;
  return h.count * kMinRecordBits <= payload_bytes * 8;
}

// A Despawn's ids: count deltas, each at least 1 and none wrapping past 2^64, filling the
// payload exactly.
bool readIds(std::span<const std::uint8_t> payload, std::size_t count,
             std::vector<std::uint64_t>& ids) {
  ids.reserve(count);
  std::size_t at = 0;
  std::uint64_t prev = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::optional<std::uint64_t> delta = readLeb128(payload, at);
    if (!delta || *delta == 0 || *delta > ~prev) return false;
    prev += *delta;
    ids.push_back(prev);
  }
  return at == payload.size();
}

}  // namespace

std::vector<std::uint8_t> encodeFrame(const FrameHeader& h, std::span<const std::uint8_t> payload,
                                      std::uint64_t token) {
  std::vector<std::uint8_t> out;
  encodeFrameInto(h, payload, token, out);
  return out;
}

void encodeFrameInto(const FrameHeader& h, std::span<const std::uint8_t> payload,
                     std::uint64_t token, std::vector<std::uint8_t>& out) {
  if (h.count > kMaxFrameCount) throw std::invalid_argument("encodeFrame: count over 2^14 - 1");
  out.clear();
  out.reserve(kMaxFrameOverheadBytes + payload.size());
  out.push_back(std::uint8_t(kFrameTag | std::uint8_t(h.kind)));
  for (std::size_t i = 0; i < kSeqBytes; ++i) out.push_back(std::uint8_t(h.seq >> (8 * i)));
  appendLeb128(out, h.tick);
  appendLeb128(out, h.count);
  out.insert(out.end(), payload.begin(), payload.end());
  std::uint32_t crc = keyedCrc(token, out);
  for (std::size_t i = 0; i < kChecksumBytes; ++i) out.push_back(std::uint8_t(crc >> (8 * i)));
  if (out.size() > kMaxDatagramBytes)
    throw std::invalid_argument("encodeFrame: over kMaxDatagramBytes");
}

bool appendDespawnId(std::vector<std::uint8_t>& payload, std::uint64_t prev, std::uint64_t id,
                     std::size_t max_bytes) {
  if (id <= prev) throw std::invalid_argument("appendDespawnId: ids must ascend");
  if (payload.size() + leb128Size(id - prev) > max_bytes) return false;
  appendLeb128(payload, id - prev);
  return true;
}

ParsedFrame parseFrame(std::span<const std::uint8_t> bytes, std::uint64_t token) {
  ParsedFrame p;
  auto drop = [&](DropReason r) {
    p.drop = r;
    return p;
  };
  if (bytes.size() > kMaxDatagramBytes) return drop(DropReason::TooLarge);
  if (bytes.size() < kMinFrameBytes) return drop(DropReason::Truncated);
  if (!knownKind(bytes[0])) return drop(DropReason::BadIdentifier);
  if (token == 0) return drop(DropReason::NotReady);
  std::span<const std::uint8_t> body = bytes.first(bytes.size() - kChecksumBytes);
  std::uint32_t stored = 0;
  for (std::size_t i = 0; i < kChecksumBytes; ++i)
    stored |= std::uint32_t(bytes[body.size() + i]) << (8 * i);
  if (stored != keyedCrc(token, body)) return drop(DropReason::BadChecksum);
  FrameHeader& h = p.frame.header;
  h.kind = FrameKind(bytes[0] & 0x0F);
  for (std::size_t i = 0; i < kSeqBytes; ++i) h.seq |= std::uint32_t(body[kSeqAt + i]) << (8 * i);
  std::size_t at = kSeqAt + kSeqBytes;
  std::optional<std::uint64_t> tick = readLeb128(body, at);
  std::optional<std::uint64_t> count =
      tick ? readLeb128(body, at, kMaxCountBytes) : std::optional<std::uint64_t>();
  if (!tick || !count) return drop(DropReason::Malformed);
  h.tick = *tick;
  h.count = std::size_t(*count);
  p.frame.payload = body.subspan(at);
  if (!plausibleCount(h, p.frame.payload.size())) return drop(DropReason::OutOfRange);
  if (h.kind == FrameKind::Despawn && !readIds(p.frame.payload, h.count, p.frame.ids))
    return drop(DropReason::OutOfRange);
  return p;
}

}  // namespace zonesim::gateway
