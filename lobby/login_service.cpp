#include "lobby/login_service.h"

#include <utility>

#include "auth/connect_token.h"

namespace zonesim::lobby {

LoginService::LoginService(auth::AuthKey key, GatewayDirectory& directory,
                           const LoginSettings& settings)
    : key_(std::move(key)), directory_(directory), settings_(settings) {}

std::uint64_t LoginService::nextPlayerId(std::uint16_t gateway_id) {
  // The gateway's id in bits 32-47, as ids a gateway issues itself: unique across gateways,
  // and across lobby restarts through the random incarnation.
  return (std::uint64_t{settings_.incarnation} << 48) | (std::uint64_t{gateway_id} << 32) |
         ++player_counters_[gateway_id];
}

std::optional<gateway::Bytes> LoginService::handle(std::span<const std::uint8_t> bytes,
                                                   const gateway::Endpoint& from,
                                                   std::int64_t now_ns, std::uint64_t now_unix_ms) {
  gateway::LobbyVerified v = gateway::verifyLobbyDatagram(bytes, gateway::LobbyDirection::ToLobby);
  if (!v.ok()) {
    drops_.add(v.reason);
    return std::nullopt;
  }
  ++counters_.requests;
  prune(now_unix_ms);
  std::uint64_t nonce = v.datagram->msg_as_LoginRequest()->request_nonce();
  RequestKey key{from, nonce};
  if (auto it = answered_.find(key); it != answered_.end()) {
    ++counters_.repeated;
    return it->second.reply;
  }
  std::size_t live = directory_.live(now_ns);
  started_ = started_ || live >= settings_.expect_gateways;
  if (!started_ && live > 0) {
    ++counters_.refused_starting;
    return gateway::encodeLoginRefused(nonce, true,
                                       "waiting for gateways: " + std::to_string(live) + " of " +
                                           std::to_string(settings_.expect_gateways) + " reported");
  }
  const GatewayEntry* g = directory_.pick(now_ns, now_unix_ms);
  if (g == nullptr) {
    bool none = live == 0;
    ++(none ? counters_.refused_no_gateway : counters_.refused_full);
    return gateway::encodeLoginRefused(
        nonce, true, none ? "no gateway has reported to the lobby" : "every gateway is full");
  }
  auth::ConnectToken t;
  t.gateway_id = g->last.gateway_id;
  t.player_id = nextPlayerId(t.gateway_id);
  t.client_address = from.address;
  t.client_port = from.port;
  t.expiry_unix_ms = now_unix_ms + settings_.token_lifetime_ms;
  auth::TokenBytes signed_token = auth::signToken(t, key_);
  gateway::LoginGrant grant{nonce,           t.player_id,      t.gateway_id,
                            g->last.address, t.expiry_unix_ms, signed_token};
  gateway::Bytes reply = gateway::encodeLoginGranted(grant);
  directory_.granted(t.gateway_id, t.expiry_unix_ms);
  answered_.emplace(key, Answered{reply, t.expiry_unix_ms});
  ++counters_.granted;
  return reply;
}

void LoginService::prune(std::uint64_t now_unix_ms) {
  if (now_unix_ms < next_prune_ms_) return;
  next_prune_ms_ = now_unix_ms + 1000;
  std::erase_if(answered_, [&](const auto& kv) { return kv.second.expiry_unix_ms <= now_unix_ms; });
}

}  // namespace zonesim::lobby
