#pragma once
// Checks every datagram from the network before anything reads it: size limits, the file
// identifier, the FlatBuffers Verifier (bounded depth and table count), then value ranges, since
// the Verifier checks structure only. Both the gateway and the clients use it: neither trusts
// the other side. The lean downlink frames (StateBatch, Spawn, Despawn) have their own parser
// with the same order of checks and the same drop reasons (wire/downlink_frame.h).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "client_protocol_generated.h"
#include "wire/drop_reason.h"

namespace zonesim::gateway {

/// Smallest buffer that can hold a root offset and a file identifier (before the checksum).
inline constexpr std::size_t kMinDatagramBytes = 8;
/// Longest player name accepted in a Hello.
inline constexpr std::size_t kMaxNameBytes = 64;
/// Longest connect or resume token accepted in a Hello: room above today's 57 and 56 bytes for
/// a later version; the exact size is the token check's business (auth/).
inline constexpr std::size_t kMaxConnectTokenBytes = 128;
/// Rows of a leaderboard a player may ask for (they fit one datagram; the zones' reply topic
/// holds as many: idl/topics.h, dds::kLeaderboardRows, checked in gateway/zone_link.cpp).
inline constexpr std::size_t kMaxLeaderboardRows = 32;
/// Earlier inputs one Input may carry again.
inline constexpr std::size_t kMaxEarlierInputs = 8;
/// A transaction outcome's reason, at most (the zones cut theirs to it).
inline constexpr std::size_t kMaxReasonBytes = 160;
/// Transaction kinds (ledger::Kind: trade, loot, purchase, score) and outcome statuses
/// (ledger::TxStatus: committed, already committed, conflict, failed) a datagram may carry.
inline constexpr std::uint8_t kMaxTransactionKind = 4;
inline constexpr std::uint8_t kMaxTransactionStatus = 3;
/// Slack on |move| <= 1 for rounding on the client.
inline constexpr float kMoveEpsilon = 1e-3f;
/// Positions beyond this magnitude (metres) are nonsense whatever the scene.
inline constexpr float kMaxCoordinate = 1e7f;
/// Speeds beyond this (m/s) are nonsense for anything zonesim simulates.
inline constexpr float kMaxSpeed = 1e4f;
/// Entity kinds: 0 NPC, 1 avatar, 2 rigid body, 3 particle emitter, 4 unique item.
inline constexpr std::uint8_t kMaxEntityKind = 4;

/// Which side receives: the set of acceptable messages and checks differ.
enum class Direction { ToGateway, ToClient };

/// A datagram that passed every check, or why it did not.
struct Verified {
  const proto::Datagram* datagram = nullptr;
  DropReason reason = DropReason::Malformed;
  bool ok() const { return datagram != nullptr; }
};

/// Limits handed to the FlatBuffers Verifier: nesting depth and tables per buffer.
struct VerifierLimits {
  unsigned max_depth = 4, max_tables = 8;
};

/// The checks every protocol's datagram gets before its own, in order: size limits, the
/// CRC-32C trailer (dropped from bytes on success), the file identifier, the FlatBuffers
/// Verifier (with alignment checks). Returns the reason to drop, or nullopt.
std::optional<DropReason> checkFraming(std::span<const std::uint8_t>& bytes,
                                       bool (*has_identifier)(const void*),
                                       bool (*verify)(flatbuffers::Verifier&),
                                       VerifierLimits limits);

/// Runs all checks in order (sizes, the checksum trailer, the Verifier on the bytes before it,
/// byte 0 not a lean frame's, values); the returned pointer aliases bytes. bytes must be 4-byte
/// aligned.
Verified verifyDatagram(std::span<const std::uint8_t> bytes, Direction direction);

/// True if codec parameters describe a grid and steps a client can work with.
bool validCodec(const proto::CodecParams& c);

}  // namespace zonesim::gateway
