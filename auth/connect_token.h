#pragma once
// Connect tokens: the lobby signs, for one player, which gateway it may join, from which UDP
// address and port, and until when; the gateway checks all four before it opens a session.
// The client carries the token as opaque bytes and cannot change any of it without the key.
//
// Wire form (57 bytes, little-endian): version u8 = 1, gateway_id u16, client_port u16,
// client_address u32 (IPv4), player_id u64, expiry_unix_ms u64, then HMAC-SHA-256 over the
// 25 bytes before it under the cluster's key.
//
// The port is bound as well as the address: simulated players share one host's address, and
// without the port any of them could replay another's token. A player therefore logs in from
// the socket it then plays from. A NAT that maps one socket to different ports per destination
// (a symmetric NAT) would defeat this; the cluster networks zonesim targets have none.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "auth/auth_key.h"
#include "auth/sha256.h"

namespace zonesim::auth {

/// The version byte of the wire form this code writes and accepts.
inline constexpr std::uint8_t kConnectTokenVersion = 1;
/// Bytes signed: everything but the tag.
inline constexpr std::size_t kConnectTokenBodyBytes = 25;
/// Bytes of a whole token, tag included.
inline constexpr std::size_t kConnectTokenBytes = kConnectTokenBodyBytes + kSha256Bytes;

/// What a connect token grants.
struct ConnectToken {
  std::uint64_t player_id = 0;
  std::uint16_t gateway_id = 0;
  std::uint32_t client_address = 0;  ///< IPv4, host byte order
  std::uint16_t client_port = 0;     ///< host byte order
  std::uint64_t expiry_unix_ms = 0;  ///< valid while the gateway's wall clock is before this
  friend bool operator==(const ConnectToken&, const ConnectToken&) = default;
};

/// A token's wire form.
using TokenBytes = std::array<std::uint8_t, kConnectTokenBytes>;

/// Signs a token.
TokenBytes signToken(const ConnectToken& token, const AuthKey& key);

/// Why a gateway refuses a token, or Ok.
enum class TokenCheck : std::uint8_t {
  Ok,
  Forged,        ///< wrong size or version, or the tag does not match: not made with our key
  WrongGateway,  ///< signed for another gateway
  Expired,       ///< its expiry has passed
  WrongAddress,  ///< presented from another address or port than it was signed for
};

/// The outcome of checking a token, with its fields when the tag matched.
struct TokenVerdict {
  TokenCheck check = TokenCheck::Forged;
  ConnectToken token;  ///< meaningful unless check is Forged
};

/// Checks the tag first (no field of an unauthenticated token is believed), then the gateway,
/// the expiry against now_unix_ms and the sender's address and port.
TokenVerdict checkToken(std::span<const std::uint8_t> bytes, const AuthKey& key,
                        std::uint16_t gateway_id, std::uint32_t from_address,
                        std::uint16_t from_port, std::uint64_t now_unix_ms);

/// Milliseconds since the Unix epoch by the wall clock (hosts of a cluster keep it in step).
std::uint64_t unixNowMs();

}  // namespace zonesim::auth
