#include "wire/datagram_checksum.h"

#include <array>

namespace zonesim::gateway {

namespace {

constexpr std::uint32_t kCastagnoliReflected = 0x82F63B78u;

constexpr std::array<std::uint32_t, 256> makeTable() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? (c >> 1) ^ kCastagnoliReflected : c >> 1;
    t[i] = c;
  }
  return t;
}

constexpr std::array<std::uint32_t, 256> kTable = makeTable();

// The register after bytes, from register c (pre- and post-inversion left to the callers).
std::uint32_t update(std::uint32_t c, std::span<const std::uint8_t> bytes) {
  for (std::uint8_t b : bytes) c = kTable[(c ^ b) & 0xFFu] ^ (c >> 8);
  return c;
}

}  // namespace

std::uint32_t crc32c(std::span<const std::uint8_t> bytes) {
  return update(0xFFFFFFFFu, bytes) ^ 0xFFFFFFFFu;
}

std::uint32_t crc32c(std::span<const std::uint8_t> key, std::span<const std::uint8_t> bytes) {
  return update(update(0xFFFFFFFFu, key), bytes) ^ 0xFFFFFFFFu;
}

void appendChecksum(std::vector<std::uint8_t>& bytes) {
  std::uint32_t c = crc32c(bytes);
  for (std::size_t i = 0; i < kChecksumBytes; ++i) bytes.push_back(std::uint8_t(c >> (8 * i)));
}

bool checksumMatches(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kChecksumBytes) return false;
  std::size_t body = bytes.size() - kChecksumBytes;
  std::uint32_t stored = 0;
  for (std::size_t i = 0; i < kChecksumBytes; ++i)
    stored |= std::uint32_t(bytes[body + i]) << (8 * i);
  return stored == crc32c(bytes.first(body));
}

}  // namespace zonesim::gateway
