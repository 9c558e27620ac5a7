#pragma once
// Avatar states between topology nodes travel as the gateway's lean StateBatch frame
// (wire/downlink_frame.h) carrying the quantised codec's records (dr/state_codec.h): the same
// bytes a client of the real cluster decodes, so bandwidth compares like with like. The
// frame's checksum key is the game's token, handed to every node at start in place of the
// gateway's Welcome.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "dr/state_codec.h"
#include "wire/drop_reason.h"

namespace zonesim::topo {

/// Avatars are entity kind 1, as in the cluster.
inline constexpr std::uint8_t kAvatarKind = 1;

/// Entity id of a player's avatar: ids start at 1, since the codec's id deltas start from 0.
inline std::uint64_t avatarId(std::uint32_t player) {
  return std::uint64_t(player) + 1;
}
inline std::uint32_t playerOf(std::uint64_t avatar_id) {
  return std::uint32_t(avatar_id - 1);
}

/// One frame of entities (ascending ids) sampled at tick. Throws std::invalid_argument if
/// they do not fit one datagram (a caller's bug: a duel arena holds a few dozen).
std::vector<std::uint8_t> encodeStateFrame(const dr::StateCodec& codec, std::uint64_t token,
                                           std::uint32_t seq, std::uint64_t tick,
                                           std::span<const dr::WireEntity> entities);

/// What a received state frame held, or why it was dropped.
struct DecodedStates {
  std::uint64_t tick = 0;
  std::vector<dr::WireEntity> entities;
  std::optional<gateway::DropReason> drop;
};

/// Every check of the cluster's client (frame, then codec), in its order.
DecodedStates decodeStateFrame(const dr::StateCodec& codec, std::span<const std::uint8_t> bytes,
                               std::uint64_t token);

}  // namespace zonesim::topo
