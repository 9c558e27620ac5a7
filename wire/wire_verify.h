#pragma once
// Checks every datagram from the network before anything reads it: size limits, the file
// identifier, the FlatBuffers Verifier (bounded depth and table count), then value ranges, since
// the Verifier checks structure only. Both the gateway and the clients use it: neither trusts
// the other side. The lean downlink frames (StateBatch, Spawn, Despawn) have their own parser
// with the same order of checks and the same drop reasons (wire/downlink_frame.h).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "client_protocol_generated.h"

namespace zonesim::gateway {

/// Largest datagram either side sends or accepts (fits one Ethernet MTU with headers).
inline constexpr std::size_t kMaxDatagramBytes = 1400;
/// Smallest buffer that can hold a root offset and a file identifier (before the checksum).
inline constexpr std::size_t kMinDatagramBytes = 8;
/// Longest player name accepted in a Hello.
inline constexpr std::size_t kMaxNameBytes = 64;
/// Longest connect token accepted in a Hello: room above today's 57 bytes for a later version;
/// the exact size is the token check's business (auth/connect_token.h).
inline constexpr std::size_t kMaxConnectTokenBytes = 128;
/// Slack on |move| <= 1 for rounding on the client.
inline constexpr float kMoveEpsilon = 1e-3f;
/// Positions beyond this magnitude (metres) are nonsense whatever the scene.
inline constexpr float kMaxCoordinate = 1e7f;
/// Speeds beyond this (m/s) are nonsense for anything zonesim simulates.
inline constexpr float kMaxSpeed = 1e4f;
/// Entity kinds: 0 NPC, 1 avatar, 2 rigid body, 3 particle emitter.
inline constexpr std::uint8_t kMaxEntityKind = 3;

/// Why a datagram was dropped; each is counted separately.
enum class DropReason : std::uint8_t {
  TooLarge,        ///< over kMaxDatagramBytes
  Truncated,       ///< too short to be a FlatBuffer (or a lean frame)
  BadIdentifier,   ///< not a ZSCP buffer (nor a lean frame of a known kind)
  Malformed,       ///< the Verifier rejected its structure (a frame: its tick or count)
  NoMessage,       ///< union empty or of an unknown type
  UnexpectedType,  ///< a message that never travels in this direction (or not as FlatBuffers)
  OutOfRange,      ///< a value out of range (NaN, |move| > 1, ...)
  BadToken,        ///< no session has this token (forged or expired)
  WrongAddress,    ///< a real token sent from another address than the session's
  NotReady,        ///< input for a session that has no avatar yet; a frame before the Welcome
  StaleInput,      ///< input seq not newer than the last forwarded one
  SessionLimit,    ///< Hello refused: too many sessions
  RateLimited,     ///< a session sending faster than its per-client rate limit
  BadChecksum,     ///< the CRC-32C trailer does not match: corrupted on the way, or a lean
                   ///< frame (keyed by the token) made for another session
  // Hellos refused by a gateway that requires connect tokens (started with a cluster key):
  TokenMissing,       ///< the Hello carries no connect token
  TokenForged,        ///< the token was not signed with the cluster's key (or is malformed)
  TokenExpired,       ///< the token's expiry has passed
  TokenWrongGateway,  ///< the token was signed for another gateway
  TokenWrongAddress,  ///< the token is replayed from another address or port than it names
  TokenReused,        ///< the token already opened a session here (each opens one)
  Count
};

/// Stable snake_case name used in metrics.
const char* dropReasonName(DropReason reason);

/// Counts of dropped datagrams per reason.
class DropCounters {
 public:
  void add(DropReason r, std::uint64_t n = 1) { counts_[std::size_t(r)] += n; }
  std::uint64_t operator[](DropReason r) const { return counts_[std::size_t(r)]; }
  /// All drops together.
  std::uint64_t total() const;

 private:
  std::array<std::uint64_t, std::size_t(DropReason::Count)> counts_{};
};

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
