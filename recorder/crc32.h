#pragma once
// CRC-32 (IEEE 802.3, reflected, as zlib's crc32): what Python's zlib.crc32 computes, so the
// inspector's reader checks a recording's chunks without a C extension.

#include <cstddef>
#include <cstdint>

namespace zonesim::recording {

std::uint32_t crc32(const std::uint8_t* data, std::size_t size);

}  // namespace zonesim::recording
