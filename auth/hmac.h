#pragma once
// HMAC-SHA-256 (RFC 2104, FIPS 198-1) and a comparison of tags whose time does not depend on
// where they differ, so a forger cannot find a valid tag byte by byte from reply timing.

#include <cstdint>
#include <span>

#include "auth/sha256.h"

namespace zonesim::auth {

/// HMAC-SHA-256 of message under key (any key length; longer than a block is hashed first).
Digest hmacSha256(std::span<const std::uint8_t> key, std::span<const std::uint8_t> message);

/// True if a and b are equal; looks at every byte whatever it finds (sizes are not secret).
bool constantTimeEqual(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b);

}  // namespace zonesim::auth
