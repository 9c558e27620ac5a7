#pragma once
// A small deterministic generator (PCG32, O'Neill 2014) per entity: the stream is derived from
// the entity id and the scene seed, and only the 64-bit state travels with a migrating entity.

#include <cstdint>

namespace zonesim {

class Pcg32 {
 public:
  Pcg32(std::uint64_t seed, std::uint64_t stream) : inc_((stream << 1u) | 1u) {
    next();
    state_ += seed;
    next();
  }
  /// Rebuilds a generator mid-sequence (after migration).
  static Pcg32 fromState(std::uint64_t state, std::uint64_t stream) {
    Pcg32 g(0, stream);
    g.state_ = state;
    return g;
  }

  std::uint32_t next() {
    std::uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
    auto rot = std::uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() {
    std::uint64_t hi = next(), lo = next();
    return double(((hi << 32) | lo) >> 11) * 0x1.0p-53;
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  std::uint64_t state() const { return state_; }

 private:
  std::uint64_t state_ = 0;
  std::uint64_t inc_;
};

}  // namespace zonesim
