#include "topologies/hit_frame.h"

#include "topologies/keyed_frame.h"
#include "wire/leb128.h"

namespace zonesim::topo {

using frame::appendU32;
using frame::readU32;

std::vector<std::uint8_t> encodeHit(const HitClaim& hit, std::uint64_t token) {
  std::vector<std::uint8_t> out{kHitTag};
  appendU32(out, hit.attacker);
  appendU32(out, hit.target);
  gateway::appendLeb128(out, hit.tick);
  frame::appendKeyedCrc(out, token);
  return out;
}

ParsedHit parseHit(std::span<const std::uint8_t> bytes, std::uint64_t token) {
  using gateway::DropReason;
  ParsedHit out;
  constexpr std::size_t kMin = 1 + 4 + 4 + 1 + 4;
  if (bytes.size() > gateway::kMaxDatagramBytes) return {{}, DropReason::TooLarge};
  if (bytes.size() < kMin) return {{}, DropReason::Truncated};
  if (bytes[0] != kHitTag) return {{}, DropReason::BadIdentifier};
  if (!frame::keyedCrcMatches(bytes, token)) return {{}, DropReason::BadChecksum};
  std::span<const std::uint8_t> body = bytes.first(bytes.size() - 4);
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
