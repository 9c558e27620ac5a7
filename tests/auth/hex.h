#pragma once
// Hex text of bytes and back, for comparing digests with published test vectors.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace zonesim::auth::test {

/// Lower-case hex of bytes.
inline std::string hex(std::span<const std::uint8_t> bytes) {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (std::uint8_t b : bytes) {
    s += digits[b >> 4];
    s += digits[b & 15];
  }
  return s;
}

/// The bytes of a string's characters.
inline std::vector<std::uint8_t> bytesOf(std::string_view text) {
  return {text.begin(), text.end()};
}

}  // namespace zonesim::auth::test
