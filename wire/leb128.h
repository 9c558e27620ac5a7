#pragma once
// Unsigned LEB128 (DWARF, protobuf, WebAssembly): 7 bits a byte, low bits first, the high bit
// set on every byte but the last. The lean downlink frame's tick, count and despawn id deltas
// are small most of the time, and this spends a byte per 7 significant bits of them.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace zonesim::gateway {

/// The most bytes a 64-bit number takes.
inline constexpr std::size_t kMaxLeb128Bytes = 10;

/// Bytes v takes.
inline std::size_t leb128Size(std::uint64_t v) {
  std::size_t n = 1;
  while (v >>= 7) ++n;
  return n;
}

/// Appends v.
inline void appendLeb128(std::vector<std::uint8_t>& out, std::uint64_t v) {
  for (; v >= 0x80; v >>= 7) out.push_back(std::uint8_t(v | 0x80));
  out.push_back(std::uint8_t(v));
}

/// Reads a number of at most max_bytes bytes at `at` and moves `at` past it; nullopt if it runs
/// past the end or max_bytes, overflows 64 bits, or is padded with a zero byte (each number has
/// one encoding, so a frame has one too).
inline std::optional<std::uint64_t> readLeb128(std::span<const std::uint8_t> bytes, std::size_t& at,
                                               std::size_t max_bytes = kMaxLeb128Bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < max_bytes && i < kMaxLeb128Bytes && at < bytes.size(); ++i) {
    std::uint8_t b = bytes[at++];
    if ((i == kMaxLeb128Bytes - 1 && b > 1) || (i > 0 && b == 0)) return std::nullopt;
    v |= std::uint64_t(b & 0x7f) << (7 * i);
    if ((b & 0x80) == 0) return v;
  }
  return std::nullopt;
}

}  // namespace zonesim::gateway
