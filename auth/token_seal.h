#pragma once
// The seal both signed tokens share (connect_token.h, resume_token.h): a version byte, a body,
// and an HMAC-SHA-256 tag of version and body under the cluster's key.

#include <cstddef>
#include <cstdint>
#include <span>

#include "auth/auth_key.h"

namespace zonesim::auth {

/// Writes the tag of token[0, body_bytes) into token[body_bytes, end) (32 bytes).
void sealToken(std::span<std::uint8_t> token, std::size_t body_bytes, const AuthKey& key);

/// True if `token` has `size` bytes, starts with `version`, and its tag is the key's for its
/// first `body_bytes` (compared in constant time).
bool tokenSealed(std::span<const std::uint8_t> token, std::size_t size, std::uint8_t version,
                 std::size_t body_bytes, const AuthKey& key);

}  // namespace zonesim::auth
