#pragma once
// Resume tokens: what a gateway gives a player in its Welcome so that, when the gateway dies,
// the player can say Hello to a restarted gateway, or to another of the cluster, and get the
// same avatar back. The zones keep an avatar whose player fell silent for a grace period
// (zone_node --orphan-grace), and a spawn request for a player they know re-announces its
// avatar with the last input applied: the token only has to prove who the player is.
//
// Wire form (56 bytes, little-endian): version u8 = 1, kind u8, client_port u16,
// client_address u32 (IPv4), player_id u64, expiry_unix_ms u64, then HMAC-SHA-256 over the
// 24 bytes before it under the key the cluster's gateways share. Unlike a connect token it
// names no gateway (any gateway of the cluster may take the player back) and may be used more
// than once (a player may lose several gateways). It is bound to the socket the player plays
// from, as a connect token is, so a sniffed one is useless from elsewhere. Its length differs
// from a connect token's (57 bytes), so one can never pass for the other.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "auth/auth_key.h"
#include "auth/sha256.h"

namespace zonesim::auth {

/// The version byte of the wire form this code writes and accepts.
inline constexpr std::uint8_t kResumeTokenVersion = 1;
/// Bytes signed: everything but the tag.
inline constexpr std::size_t kResumeTokenBodyBytes = 24;
/// Bytes of a whole token, tag included.
inline constexpr std::size_t kResumeTokenBytes = kResumeTokenBodyBytes + kSha256Bytes;

/// Whom a resume token takes back.
struct ResumeToken {
  std::uint64_t player_id = 0;
  std::uint8_t kind = 0;             ///< the player's kind (common/player_kind.h)
  std::uint32_t client_address = 0;  ///< IPv4, host byte order
  std::uint16_t client_port = 0;     ///< host byte order
  std::uint64_t expiry_unix_ms = 0;  ///< valid while the gateway's wall clock is before this
  friend bool operator==(const ResumeToken&, const ResumeToken&) = default;
};

using ResumeBytes = std::array<std::uint8_t, kResumeTokenBytes>;

/// Signs a resume token.
ResumeBytes signResume(const ResumeToken& token, const AuthKey& key);

/// Why a gateway refuses a resume token, or Ok.
enum class ResumeCheck : std::uint8_t {
  Ok,
  Forged,        ///< wrong size or version, or the tag does not match our key
  Expired,       ///< its expiry has passed
  WrongAddress,  ///< presented from another address or port than it was signed for
};

/// The outcome of checking a resume token, with its fields when the tag matched.
struct ResumeVerdict {
  ResumeCheck check = ResumeCheck::Forged;
  ResumeToken token;  ///< meaningful unless check is Forged
};

/// Checks the tag first (nothing of an unauthenticated token is believed), then the expiry
/// against now_unix_ms and the sender's address and port.
ResumeVerdict checkResume(std::span<const std::uint8_t> bytes, const AuthKey& key,
                          std::uint32_t from_address, std::uint16_t from_port,
                          std::uint64_t now_unix_ms);

}  // namespace zonesim::auth
