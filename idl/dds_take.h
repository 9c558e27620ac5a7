#pragma once
// Draining a reader: every available sample, taken in batches of loaned buffers.

#include <dds/dds.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>

#include "idl/dds_entity.h"

namespace zonesim::dds {

/// Takes every available sample of type T from reader, calling f(const T&) on each valid one
/// while its loan lasts; returns how many samples were taken. Throws DdsError on failure.
template <typename T, typename F>
std::size_t takeAll(dds_entity_t reader, F&& f) {
  constexpr std::uint32_t kBatch = 64;
  std::size_t total = 0;
  void* samples[kBatch];
  dds_sample_info_t infos[kBatch];
  for (;;) {
    std::fill(std::begin(samples), std::end(samples), nullptr);  // nullptr: Cyclone loans
    int n = check(dds_take(reader, samples, infos, kBatch, kBatch), "dds_take");
    for (int i = 0; i < n; ++i)
      if (infos[i].valid_data) f(*static_cast<const T*>(samples[i]));
    if (n > 0) dds_return_loan(reader, samples, n);
    total += std::size_t(n);
    if (std::uint32_t(n) < kBatch) return total;
  }
}

}  // namespace zonesim::dds
