#pragma once
// The admission check of a gateway started with the cluster's key: a Hello opens a session only
// with a connect token the lobby signed for this gateway, still valid, presented from the
// address and port it names, and not used here before. Each refusal has its own drop reason.

#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>

#include "auth/auth_key.h"
#include "wire/udp_socket.h"
#include "wire/wire_verify.h"

namespace zonesim::gateway {

/// A token that passed every check: the player it admits, until when.
struct Admitted {
  std::uint64_t player_id = 0;
  std::uint64_t expiry_unix_ms = 0;
};

/// Checks connect tokens and remembers the ones used until they expire.
class TokenGate {
 public:
  /// Checks tokens signed with key for gateway_id.
  TokenGate(auth::AuthKey key, std::uint16_t gateway_id);

  /// The player the token admits, or why it is refused. `token` empty: TokenMissing.
  std::optional<Admitted> check(std::span<const std::uint8_t> token, const Endpoint& from,
                                std::uint64_t now_unix_ms, DropReason& refused);
  /// Records that a token opened a session: the same token is refused (TokenReused) until it
  /// expires, when the check refuses it anyway. Since a player id's avatar is despawned for
  /// good when its session ends (zones remember despawns), a second session could not work.
  void consume(const Admitted& a);
  /// Tokens that opened a session since start.
  std::uint64_t admitted() const { return admitted_; }
  /// Tokens remembered as used (not yet expired).
  std::size_t remembered() const { return used_.size(); }

 private:
  /// Forgets used tokens that have expired, at most once a second.
  void prune(std::uint64_t now_unix_ms);

  auth::AuthKey key_;
  std::uint16_t gateway_id_;
  std::unordered_map<std::uint64_t, std::uint64_t> used_;  // player id -> token expiry
  std::uint64_t next_prune_ms_ = 0;
  std::uint64_t admitted_ = 0;
};

}  // namespace zonesim::gateway
