#include "auth/token_seal.h"

#include <algorithm>

#include "auth/hmac.h"

namespace zonesim::auth {

void sealToken(std::span<std::uint8_t> token, std::size_t body_bytes, const AuthKey& key) {
  Digest tag = hmacSha256(key.bytes(), token.first(body_bytes));
  std::copy(tag.begin(), tag.end(), token.begin() + std::ptrdiff_t(body_bytes));
}

bool tokenSealed(std::span<const std::uint8_t> token, std::size_t size, std::uint8_t version,
                 std::size_t body_bytes, const AuthKey& key) {
  if (token.size() != size || token[0] != version) return false;
  Digest tag = hmacSha256(key.bytes(), token.first(body_bytes));
  return constantTimeEqual(tag, token.subspan(body_bytes));
}

}  // namespace zonesim::auth
