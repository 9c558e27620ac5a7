#pragma once
// The true trajectory of sampled entities (dr/truth_sample.h), one CSV line per entity and
// tick as the publish phase saw it: deploy/truth_error.py joins it with what clients showed.

#include <cstdint>
#include <cstdio>
#include <string>

#include "zone_node/entity_store.h"

namespace zonesim::zone {

class TruthLog {
 public:
  /// Opens path (truncating) for every k-th id; throws if it cannot. With every = 0 or an
  /// empty path there is no file and record() does nothing.
  TruthLog(const std::string& path, std::uint32_t every);
  ~TruthLog();
  TruthLog(const TruthLog&) = delete;
  TruthLog& operator=(const TruthLog&) = delete;

  /// Writes tick, id, kind, x, y, z of every sampled entity in the store.
  void record(std::uint64_t tick, const EntityStore& store);

 private:
  std::FILE* file_ = nullptr;
  std::uint32_t every_ = 0;
};

}  // namespace zonesim::zone
