#include "topologies/keyed_frame.h"

#include "wire/datagram_checksum.h"

namespace zonesim::topo::frame {

void appendU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}

std::uint32_t readU32(std::span<const std::uint8_t> b, std::size_t at) {
  return std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 | std::uint32_t(b[at + 2]) << 16 |
         std::uint32_t(b[at + 3]) << 24;
}

std::uint32_t keyedCrc(std::span<const std::uint8_t> body, std::uint64_t token) {
  std::uint8_t key[8];
  for (int i = 0; i < 8; ++i) key[i] = std::uint8_t(token >> (8 * i));
  return gateway::crc32c(key, body);
}

void appendKeyedCrc(std::vector<std::uint8_t>& out, std::uint64_t token) {
  appendU32(out, keyedCrc(out, token));
}

bool keyedCrcMatches(std::span<const std::uint8_t> bytes, std::uint64_t token) {
  return keyedCrc(bytes.first(bytes.size() - 4), token) == readU32(bytes, bytes.size() - 4);
}

}  // namespace zonesim::topo::frame
