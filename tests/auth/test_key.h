#pragma once
// A deterministic 32-byte key per seed, for the token tests: two seeds give two keys.
#include <cstdint>
#include <vector>

#include "auth/auth_key.h"

namespace zonesim::auth {

inline AuthKey testKey(std::uint8_t seed) {
  std::vector<std::uint8_t> b(32);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = std::uint8_t(seed + i * 13);
  return AuthKey(b, "test key");
}

}  // namespace zonesim::auth
