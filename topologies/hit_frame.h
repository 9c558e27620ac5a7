#pragma once
// A claimed hit: "attacker struck target at tick". The cluster has no such message (its hits
// are the zone's to decide), so it takes the lean frame's shape: a tag byte with the high bit
// set (never a FlatBuffers datagram, never a downlink frame kind), fixed fields, and the
// CRC-32C keyed by the game's token.
//
//   offset  bytes  field
//   0       1      tag 0xC1
//   1       4      attacker player, u32 little-endian
//   5       4      target player, u32 little-endian
//   9       1-10   tick, LEB128
//   end-4   4      CRC-32C of the token (8 bytes) and bytes [0, end-4)

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "wire/drop_reason.h"

namespace zonesim::topo {

inline constexpr std::uint8_t kHitTag = 0xC1;

/// A hit as claimed.
struct HitClaim {
  std::uint32_t attacker = 0, target = 0;
  std::uint64_t tick = 0;
};

std::vector<std::uint8_t> encodeHit(const HitClaim& hit, std::uint64_t token);

/// The claim, or why it was dropped: truncated, bad_identifier (not a hit), bad_checksum,
/// malformed (tick, trailing bytes), out_of_range (a player hitting itself).
struct ParsedHit {
  HitClaim hit;
  std::optional<gateway::DropReason> drop;
};
ParsedHit parseHit(std::span<const std::uint8_t> bytes, std::uint64_t token);

}  // namespace zonesim::topo
