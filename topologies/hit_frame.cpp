#include "topologies/hit_frame.h"

#include "wire/datagram_checksum.h"
#include "wire/leb128.h"

namespace zonesim::topo {

namespace {

void appendU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}
std::uint32_t readU32(std::span<const std::uint8_t> b, std::size_t at) {
  return std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 | std::uint32_t(b[at + 2]) << 16 |
         std::uint32_t(b[at + 3]) << 24;
}
std::uint32_t keyedCrc(std::span<const std::uint8_t> body, std::uint64_t token) {
  std::uint8_t key[8];
  for (int i = 0; i < 8; ++i) key[i] = std::uint8_t(token >> (8 * i));
  return gateway::crc32c(key, body);
}

}  // namespace

std::vector<std::uint8_t> encodeHit(const HitClaim& hit, std::uint64_t token) {
  std::vector<std::uint8_t> out{kHitTag};
  appendU32(out, hit.attacker);
  appendU32(out, hit.target);
  gateway::appendLeb128(out, hit.tick);
  appendU32(out, keyedCrc(out, token));
  return out;
}

ParsedHit parseHit(std::span<const std::uint8_t> bytes, std::uint64_t token) {
  using gateway::DropReason;
  ParsedHit out;
  constexpr std::size_t kMin = 1 + 4 + 4 + 1 + 4;
  if (bytes.size() > gateway::kMaxDatagramBytes) return {{}, DropReason::TooLarge};
  if (bytes.size() < kMin) return {{}, DropReason::Truncated};
  if (bytes[0] != kHitTag) return {{}, DropReason::BadIdentifier};
  std::span<const std::uint8_t> body = bytes.first(bytes.size() - 4);
  if (keyedCrc(body, token) != readU32(bytes, bytes.size() - 4))
    return {{}, DropReason::BadChecksum};
  out.hit.attacker = readU32(body, 1);
  out.hit.target = readU32(body, 5);
  std::size_t at = 9;
  auto tick = gateway::readLeb128(body, at);
  if (!tick || at != body.size()) return {{}, DropReason::Malformed};
  out.hit.tick = *tick;
  if (out.hit.attacker == out.hit.target) return {{}, DropReason::OutOfRange};
  return out;
}

}  // namespace zonesim::topo
