#pragma once
// The lobby protocol on UDP (idl/lobby_protocol.fbs): encoders, and the checks every lobby
// datagram passes before it is read, in the order of wire_verify.h (sizes, the checksum
// trailer, the identifier, the Verifier, then values), with the same drop reasons.

#include <cstdint>
#include <span>
#include <string_view>

#include "lobby_protocol_generated.h"
#include "wire/udp_socket.h"
#include "wire/wire_encode.h"
#include "wire/wire_verify.h"

namespace zonesim::gateway {

/// Longest refusal reason the lobby sends.
inline constexpr std::size_t kMaxRefusalBytes = 200;

/// Which side receives: the lobby takes requests, the player grants and refusals.
enum class LobbyDirection { ToLobby, ToPlayer };

/// A lobby datagram that passed every check, or why it did not.
struct LobbyVerified {
  const lobby_proto::LobbyDatagram* datagram = nullptr;
  DropReason reason = DropReason::Malformed;
  bool ok() const { return datagram != nullptr; }
};

/// Runs all checks; the returned pointer aliases bytes (4-byte aligned).
LobbyVerified verifyLobbyDatagram(std::span<const std::uint8_t> bytes, LobbyDirection direction);

/// What a LoginGranted tells the player.
struct LoginGrant {
  std::uint64_t request_nonce = 0;
  std::uint64_t player_id = 0;
  std::uint16_t gateway_id = 0;
  Endpoint gateway;
  std::uint64_t expiry_unix_ms = 0;
  std::span<const std::uint8_t> connect_token;
};

/// Player -> lobby.
Bytes encodeLoginRequest(std::uint64_t request_nonce, std::string_view name);
/// Lobby -> player: a gateway and its token.
Bytes encodeLoginGranted(const LoginGrant& g);
/// Lobby -> player: no gateway now; reason is cut to kMaxRefusalBytes.
Bytes encodeLoginRefused(std::uint64_t request_nonce, bool retry, std::string_view reason);

}  // namespace zonesim::gateway
