#pragma once
// The byte order of the signed tokens' wire forms (connect and resume tokens).

#include <cstdint>

namespace zonesim::auth {

/// Writes the low `bytes` bytes of v at p, least significant first.
inline void putLittleEndian(std::uint8_t* p, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) p[i] = std::uint8_t(v >> (8 * i));
}

/// Reads `bytes` bytes at p, least significant first.
inline std::uint64_t getLittleEndian(const std::uint8_t* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= std::uint64_t(p[i]) << (8 * i);
  return v;
}

}  // namespace zonesim::auth
