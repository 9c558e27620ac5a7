#include "wire/lobby_wire.h"

#include <algorithm>

#include "wire/datagram_checksum.h"

namespace zonesim::gateway {

namespace {

// LobbyDatagram -> message table -> vector or string.
constexpr flatbuffers::uoffset_t kMaxDepth = 3;
constexpr flatbuffers::uoffset_t kMaxTables = 4;

template <typename T>
Bytes finish(flatbuffers::FlatBufferBuilder& fbb, lobby_proto::LobbyMessage type,
             flatbuffers::Offset<T> msg) {
  auto root = lobby_proto::CreateLobbyDatagram(fbb, type, msg.Union());
  lobby_proto::FinishLobbyDatagramBuffer(fbb, root);
  Bytes out(fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize());
  appendChecksum(out);
  return out;
}

bool checkValues(const lobby_proto::LobbyDatagram& d) {
  switch (d.msg_type()) {
    case lobby_proto::LobbyMessage::LoginRequest: {
      const auto* r = d.msg_as_LoginRequest();
      return r->request_nonce() != 0 &&
             (r->name() == nullptr || r->name()->size() <= kMaxNameBytes);
    }
    case lobby_proto::LobbyMessage::LoginGranted: {
      const auto* g = d.msg_as_LoginGranted();
      const auto* t = g->connect_token();
      return g->request_nonce() != 0 && g->gateway_id() != 0 && g->gateway_address() != 0 &&
             g->gateway_port() != 0 && t != nullptr && t->size() > 0 &&
             t->size() <= kMaxConnectTokenBytes;
    }
    case lobby_proto::LobbyMessage::LoginRefused: {
      const auto* r = d.msg_as_LoginRefused();
      return r->request_nonce() != 0 &&
             (r->reason() == nullptr || r->reason()->size() <= kMaxRefusalBytes);
    }
    default:
      return false;
  }
}

}  // namespace

LobbyVerified verifyLobbyDatagram(std::span<const std::uint8_t> bytes, LobbyDirection direction) {
  if (auto drop = checkFraming(bytes, &lobby_proto::LobbyDatagramBufferHasIdentifier,
                               &lobby_proto::VerifyLobbyDatagramBuffer, {kMaxDepth, kMaxTables}))
    return {nullptr, *drop};
  const lobby_proto::LobbyDatagram* d = lobby_proto::GetLobbyDatagram(bytes.data());
  lobby_proto::LobbyMessage type = d->msg_type();
  if (type == lobby_proto::LobbyMessage::NONE || type > lobby_proto::LobbyMessage::MAX ||
      d->msg() == nullptr)
    return {nullptr, DropReason::NoMessage};
  bool to_lobby = type == lobby_proto::LobbyMessage::LoginRequest;
  if (to_lobby != (direction == LobbyDirection::ToLobby))
    return {nullptr, DropReason::UnexpectedType};
  if (!checkValues(*d)) return {nullptr, DropReason::OutOfRange};
  return {d, DropReason::Count};
}

Bytes encodeLoginRequest(std::uint64_t request_nonce, std::string_view name) {
  flatbuffers::FlatBufferBuilder fbb(128);
  auto n = fbb.CreateString(name.data(), std::min(name.size(), kMaxNameBytes));
  return finish(fbb, lobby_proto::LobbyMessage::LoginRequest,
                lobby_proto::CreateLoginRequest(fbb, request_nonce, n));
}

Bytes encodeLoginGranted(const LoginGrant& g) {
  flatbuffers::FlatBufferBuilder fbb(256);
  auto t = fbb.CreateVector(g.connect_token.data(), g.connect_token.size());
  return finish(
      fbb, lobby_proto::LobbyMessage::LoginGranted,
      lobby_proto::CreateLoginGranted(fbb, g.request_nonce, g.player_id, g.gateway_id,
                                      g.gateway.address, g.gateway.port, g.expiry_unix_ms, t));
}

Bytes encodeLoginRefused(std::uint64_t request_nonce, bool retry, std::string_view reason) {
  flatbuffers::FlatBufferBuilder fbb(256);
  auto r = fbb.CreateString(reason.data(), std::min(reason.size(), kMaxRefusalBytes));
  return finish(fbb, lobby_proto::LobbyMessage::LoginRefused,
                lobby_proto::CreateLoginRefused(fbb, request_nonce, retry, r));
}

}  // namespace zonesim::gateway
