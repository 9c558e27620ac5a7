#pragma once
// Which entities the zones and the clients log for the error-against-truth report: every k-th
// id of each creating rank (the id's counter), so both sides pick the same ones without talking.

#include <cstdint>

namespace zonesim::dr {

/// Whether entity `id` is sampled when every k-th is (k = 0: none).
constexpr bool truthSampled(std::uint64_t id, std::uint32_t every) {
  constexpr std::uint64_t kCounterMask = (std::uint64_t{1} << 48) - 1;  // EntityId's counter
  return every > 0 && (id & kCounterMask) % every == 0;
}

}  // namespace zonesim::dr
