#pragma once
// Every datagram ends in a CRC-32C of the bytes before it, checked before anything else reads
// them. The Verifier checks structure only, so a flipped bit inside a position or a token would
// pass it; the UDP checksum is 16 bits and optional in IPv4, and link impairment
// (wire/link_model.h) corrupts datagrams above the kernel, where nothing else would notice.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace zonesim::gateway {

/// Bytes the checksum adds at the end of every datagram (little-endian CRC-32C).
inline constexpr std::size_t kChecksumBytes = 4;

/// CRC-32C (Castagnoli polynomial, reflected), as in iSCSI and SCTP.
std::uint32_t crc32c(std::span<const std::uint8_t> bytes);
/// CRC-32C of key followed by bytes, as if they were one buffer: a key both ends hold (a
/// session token) checks without travelling (wire/downlink_frame.h).
std::uint32_t crc32c(std::span<const std::uint8_t> key, std::span<const std::uint8_t> bytes);
/// Appends the checksum of the bytes so far.
void appendChecksum(std::vector<std::uint8_t>& bytes);
/// True if the last kChecksumBytes are the checksum of the bytes before them.
bool checksumMatches(std::span<const std::uint8_t> bytes);

}  // namespace zonesim::gateway
