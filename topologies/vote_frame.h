#pragma once
// A peer's verdict: "as of tick, voter holds these players to have lied" (docs/networking.md,
// "Topologies": majority voting). Peers share verdicts so that one a majority caught is
// excluded by everyone, even by a peer it never lied to. The hit frame's shape: a tag byte with
// the high bit set, fixed fields, the CRC-32C keyed by the game's token.
//
//   offset  bytes  field
//   0       1      tag 0xC2
//   1       4      voter player, u32 little-endian
//   5       1-10   tick, LEB128
//   then    8      suspects, u64 little-endian: bit p set = player p (a game has <= 64 players)
//   end-4   4      CRC-32C of the token (8 bytes) and bytes [0, end-4)

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "wire/drop_reason.h"

namespace zonesim::topo {

inline constexpr std::uint8_t kVoteTag = 0xC2;

/// Players as a bit set: bit p is player p.
using Suspects = std::uint64_t;

/// The bit of one player (player < 64).
inline Suspects suspectBit(std::uint32_t player) {
  return Suspects{1} << player;
}

/// A verdict as voted.
struct Vote {
  std::uint32_t voter = 0;
  std::uint64_t tick = 0;
  Suspects suspects = 0;
};

std::vector<std::uint8_t> encodeVote(const Vote& vote, std::uint64_t token);

/// The vote, or why it was dropped: too_large, truncated, bad_identifier (not a vote),
/// bad_checksum, malformed (tick, length), out_of_range (a voter of 64 or more, or one voting
/// against itself). Whether the voter is the sender and the suspects are in the game is the
/// receiver's to check.
struct ParsedVote {
  Vote vote;
  std::optional<gateway::DropReason> drop;
};
ParsedVote parseVote(std::span<const std::uint8_t> bytes, std::uint64_t token);

}  // namespace zonesim::topo
