#pragma once
// What the topology nodes' own frames (hit claims, votes) share: little-endian u32 fields and
// the trailer, a CRC-32C of the game's token (8 bytes, little-endian) and the frame's bytes,
// so that only a player of the game can make one.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace zonesim::topo::frame {

/// Appends v, little-endian.
void appendU32(std::vector<std::uint8_t>& out, std::uint32_t v);
/// The little-endian u32 at `at` (the caller checked the size).
std::uint32_t readU32(std::span<const std::uint8_t> bytes, std::size_t at);
/// CRC-32C of the token and body.
std::uint32_t keyedCrc(std::span<const std::uint8_t> body, std::uint64_t token);
/// Appends the keyed CRC of everything in out so far.
void appendKeyedCrc(std::vector<std::uint8_t>& out, std::uint64_t token);
/// Whether the last 4 bytes are the keyed CRC of the ones before (bytes holds at least 4).
bool keyedCrcMatches(std::span<const std::uint8_t> bytes, std::uint64_t token);

}  // namespace zonesim::topo::frame
