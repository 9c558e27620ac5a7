#include "auth/connect_token.h"

#include <chrono>

#include "auth/little_endian.h"
#include "auth/token_seal.h"

namespace zonesim::auth {

TokenBytes signToken(const ConnectToken& t, const AuthKey& key) {
  TokenBytes b{};
  b[0] = kConnectTokenVersion;
  putLittleEndian(&b[1], t.gateway_id, 2);
  putLittleEndian(&b[3], t.client_port, 2);
  putLittleEndian(&b[5], t.client_address, 4);
  putLittleEndian(&b[9], t.player_id, 8);
  putLittleEndian(&b[17], t.expiry_unix_ms, 8);
  sealToken(b, kConnectTokenBodyBytes, key);
  return b;
}

TokenVerdict checkToken(std::span<const std::uint8_t> bytes, const AuthKey& key,
                        std::uint16_t gateway_id, std::uint32_t from_address,
                        std::uint16_t from_port, std::uint64_t now_unix_ms) {
  TokenVerdict v;
  if (!tokenSealed(bytes, kConnectTokenBytes, kConnectTokenVersion, kConnectTokenBodyBytes, key))
    return v;
  const std::uint8_t* p = bytes.data();
  v.token.gateway_id = std::uint16_t(getLittleEndian(p + 1, 2));
  v.token.client_port = std::uint16_t(getLittleEndian(p + 3, 2));
  v.token.client_address = std::uint32_t(getLittleEndian(p + 5, 4));
  v.token.player_id = getLittleEndian(p + 9, 8);
  v.token.expiry_unix_ms = getLittleEndian(p + 17, 8);
  if (v.token.gateway_id != gateway_id)
    v.check = TokenCheck::WrongGateway;
  else if (now_unix_ms >= v.token.expiry_unix_ms)
    v.check = TokenCheck::Expired;
  else if (v.token.client_address != from_address || v.token.client_port != from_port)
    v.check = TokenCheck::WrongAddress;
  else
    v.check = TokenCheck::Ok;
  return v;
}

std::uint64_t unixNowMs() {
  using namespace std::chrono;
  return std::uint64_t(duration_cast<milliseconds>(system_clock::now().time_since_epoch()).count());
}

}  // namespace zonesim::auth
