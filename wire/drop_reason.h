#pragma once
// Why a datagram from the network is dropped, and the size limit every check starts with:
// shared by the FlatBuffers checks (wire/wire_verify.h), the lean downlink frame's parser
// (wire/downlink_frame.h) and the lobby's, none of which then needs the others' headers.

#include <array>
#include <cstddef>
#include <cstdint>

namespace zonesim::gateway {

/// Largest datagram either side sends or accepts (fits one Ethernet MTU with headers).
inline constexpr std::size_t kMaxDatagramBytes = 1400;

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
  UnknownKind,        ///< Hello refused: a player kind the gateway's scene does not list
  // Hellos with a resume token (auth/resume_token.h) refused:
  ResumeForged,        ///< not signed with the gateways' resume key (or malformed), or no key
  ResumeExpired,       ///< the resume token's expiry has passed
  ResumeWrongAddress,  ///< presented from another address or port than it names
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

}  // namespace zonesim::gateway
