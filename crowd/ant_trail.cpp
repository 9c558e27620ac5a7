#include "crowd/ant_trail.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "crowd/ant_step.h"

namespace zonesim::crowd {

std::int64_t trailDepositUnits(double deposit, double length) {
  return std::max<std::int64_t>(1, std::llround(deposit / length * kTrailScale));
}

AntTrail::AntTrail(const ai::GridMap& map, double initial, double evaporation, double dt)
    : map_(map),
      units_(std::size_t(map.width()) * std::size_t(map.height()),
             std::max<std::int64_t>(1, std::llround(initial * kTrailScale))) {
  if (!(evaporation >= 0 && evaporation <= 1))
    throw std::invalid_argument("AntTrail: evaporation " + std::to_string(evaporation) +
                                " is not a fraction in [0, 1]");
  // The same double on every rank, rounded once: evaporation is then integer arithmetic.
  keep_ = std::uint64_t(std::llround(std::pow(1.0 - evaporation, dt) * 0x1.0p32));
}

double AntTrail::total() const {
  std::int64_t sum = 0;
  for (std::int64_t t : units_) sum += t;
  return double(sum) / kTrailScale;
}

void AntTrail::evaporateAndAdd(std::span<const std::int64_t> deltas) {
  if (deltas.size() != units_.size())
    throw std::invalid_argument("AntTrail: " + std::to_string(deltas.size()) + " deltas for " +
                                std::to_string(units_.size()) + " cells");
  for (std::size_t k = 0; k < units_.size(); ++k) {
    auto kept = std::int64_t((unsigned __int128)std::uint64_t(units_[k]) * keep_ >> 32);
    units_[k] = std::max<std::int64_t>(1, kept) + deltas[k];
  }
}

std::vector<ai::Cell> AntTrail::strongestRoute(ai::Cell nest, ai::Cell food) const {
  std::vector<ai::Cell> out;
  auto strength = [&](ai::Cell, int, ai::Cell n) { return units_[index(n)]; };
  if (!strongestTrailRoute(map_, nest, food, strength, out)) return {};
  return out;
}

}  // namespace zonesim::crowd
