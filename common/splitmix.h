#pragma once
// The one 64-bit mixer of the project, for everything that must spread consecutive ids or
// counters evenly (id-set digests, LOD phases, flow destinations, counter-based draws).

#include <cstdint>

namespace zonesim {

/// SplitMix64's output function (Steele, Lea and Flood 2014), golden-ratio increment included:
/// a bijection on 64 bits whose every output bit depends on every input bit.
constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace zonesim
