#include "gateway/token_gate.h"

#include <utility>

#include "auth/connect_token.h"

namespace zonesim::gateway {

namespace {

DropReason reasonOf(auth::TokenCheck c) {
  switch (c) {
    case auth::TokenCheck::WrongGateway:
      return DropReason::TokenWrongGateway;
    case auth::TokenCheck::Expired:
      return DropReason::TokenExpired;
    case auth::TokenCheck::WrongAddress:
      return DropReason::TokenWrongAddress;
    case auth::TokenCheck::Forged:
    case auth::TokenCheck::Ok:
      break;
  }
  return DropReason::TokenForged;
}

}  // namespace

TokenGate::TokenGate(auth::AuthKey key, std::uint16_t gateway_id)
    : key_(std::move(key)), gateway_id_(gateway_id) {}

std::optional<Admitted> TokenGate::check(std::span<const std::uint8_t> token, const Endpoint& from,
                                         std::uint64_t now_unix_ms, DropReason& refused) {
  prune(now_unix_ms);
  if (token.empty()) {
    refused = DropReason::TokenMissing;
    return std::nullopt;
  }
  auth::TokenVerdict v =
      auth::checkToken(token, key_, gateway_id_, from.address, from.port, now_unix_ms);
  if (v.check != auth::TokenCheck::Ok) {
    refused = reasonOf(v.check);
    return std::nullopt;
  }
  if (used_.contains(v.token.player_id)) {
    refused = DropReason::TokenReused;
    return std::nullopt;
  }
  return Admitted{v.token.player_id, v.token.expiry_unix_ms};
}

void TokenGate::consume(const Admitted& a) {
  used_[a.player_id] = a.expiry_unix_ms;
  ++admitted_;
}

void TokenGate::prune(std::uint64_t now_unix_ms) {
  if (now_unix_ms < next_prune_ms_) return;
  next_prune_ms_ = now_unix_ms + 1000;
  std::erase_if(used_, [&](const auto& kv) { return kv.second <= now_unix_ms; });
}

}  // namespace zonesim::gateway
