#include "auth/resume_token.h"

#include "auth/little_endian.h"
#include "auth/token_seal.h"

namespace zonesim::auth {

ResumeBytes signResume(const ResumeToken& t, const AuthKey& key) {
  ResumeBytes b{};
  b[0] = kResumeTokenVersion;
  b[1] = t.kind;
  putLittleEndian(&b[2], t.client_port, 2);
  putLittleEndian(&b[4], t.client_address, 4);
  putLittleEndian(&b[8], t.player_id, 8);
  putLittleEndian(&b[16], t.expiry_unix_ms, 8);
  sealToken(b, kResumeTokenBodyBytes, key);
  return b;
}

ResumeVerdict checkResume(std::span<const std::uint8_t> bytes, const AuthKey& key,
                          std::uint32_t from_address, std::uint16_t from_port,
                          std::uint64_t now_unix_ms) {
  ResumeVerdict v;
  if (!tokenSealed(bytes, kResumeTokenBytes, kResumeTokenVersion, kResumeTokenBodyBytes, key))
    return v;
  const std::uint8_t* p = bytes.data();
  v.token.kind = p[1];
  v.token.client_port = std::uint16_t(getLittleEndian(p + 2, 2));
  v.token.client_address = std::uint32_t(getLittleEndian(p + 4, 4));
  v.token.player_id = getLittleEndian(p + 8, 8);
  v.token.expiry_unix_ms = getLittleEndian(p + 16, 8);
  if (now_unix_ms >= v.token.expiry_unix_ms)
    v.check = ResumeCheck::Expired;
  else if (v.token.client_address != from_address || v.token.client_port != from_port)
    v.check = ResumeCheck::WrongAddress;
  else
    v.check = ResumeCheck::Ok;
  return v;
}

}  // namespace zonesim::auth
