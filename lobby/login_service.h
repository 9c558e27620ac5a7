#pragma once
// Turns one login request into its reply: a connect token for the least-loaded gateway, bound
// to the address and port the request came from, or a refusal. Does no I/O, so every path is
// tested with crafted bytes. A retried request (same address, same nonce) gets the same grant
// again rather than a second player id, so retries never count twice in a gateway's load.

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <unordered_map>

#include "auth/auth_key.h"
#include "lobby/gateway_directory.h"
#include "wire/lobby_wire.h"

namespace zonesim::lobby {

/// How the lobby grants.
struct LoginSettings {
  std::uint64_t token_lifetime_ms = 30'000;  ///< from the grant to the token's expiry
  std::uint16_t incarnation = 1;  ///< bits 48-63 of the player ids issued (random per process)
  /// Logins wait (refused, retry) until this many gateways have reported, so that the first
  /// players of a cluster that is still starting do not all go to the first gateway heard of.
  std::size_t expect_gateways = 1;
};

/// What the service counted.
struct LoginCounters {
  std::uint64_t requests = 0;            ///< verified requests, retries included
  std::uint64_t granted = 0;             ///< distinct grants
  std::uint64_t repeated = 0;            ///< retries answered with the grant already made
  std::uint64_t refused_no_gateway = 0;  ///< no live gateway has reported
  std::uint64_t refused_full = 0;        ///< every live gateway is full
  std::uint64_t refused_starting = 0;    ///< fewer than expect_gateways have reported yet
};

/// Answers login requests from the directory's choice, signing tokens with the cluster key.
class LoginService {
 public:
  /// Grants from directory, which the caller keeps fed with load reports.
  LoginService(auth::AuthKey key, GatewayDirectory& directory, const LoginSettings& settings);

  /// The reply to one datagram from `from` (nullopt: dropped, counted in drops()).
  std::optional<gateway::Bytes> handle(std::span<const std::uint8_t> bytes,
                                       const gateway::Endpoint& from, std::int64_t now_ns,
                                       std::uint64_t now_unix_ms);

  /// Requests, grants and refusals since start.
  const LoginCounters& counters() const { return counters_; }
  /// Datagrams dropped by the checks, by reason.
  const gateway::DropCounters& drops() const { return drops_; }

 private:
  struct RequestKey {
    gateway::Endpoint from;
    std::uint64_t nonce;
    friend bool operator==(const RequestKey&, const RequestKey&) = default;
  };
  struct RequestKeyHash {
    std::size_t operator()(const RequestKey& k) const {
      return gateway::EndpointHash()(k.from) ^
             std::hash<std::uint64_t>()(k.nonce * 0x9e3779b97f4a7c15ULL);
    }
  };
  struct Answered {
    gateway::Bytes reply;
    std::uint64_t expiry_unix_ms;
  };
  /// Forgets answered requests whose tokens expired, at most once a second.
  void prune(std::uint64_t now_unix_ms);
  std::uint64_t nextPlayerId(std::uint16_t gateway_id);

  auth::AuthKey key_;
  GatewayDirectory& directory_;
  LoginSettings settings_;
  std::unordered_map<RequestKey, Answered, RequestKeyHash> answered_;
  std::map<std::uint16_t, std::uint32_t> player_counters_;  // per gateway
  std::uint64_t next_prune_ms_ = 0;
  bool started_ = false;  // expect_gateways reported once: from then on, whoever is live serves
  LoginCounters counters_;
  gateway::DropCounters drops_;
};

}  // namespace zonesim::lobby
