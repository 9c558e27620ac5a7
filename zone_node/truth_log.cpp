#include "zone_node/truth_log.h"

#include <stdexcept>

#include "dr/truth_sample.h"

namespace zonesim::zone {

TruthLog::TruthLog(const std::string& path, std::uint32_t every) : every_(every) {
  if (every == 0 || path.empty()) return;
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) throw std::runtime_error("cannot write " + path);
  std::fprintf(file_, "tick,id,kind,x,y,z\n");
}

TruthLog::~TruthLog() {
  if (file_ != nullptr) std::fclose(file_);
}

void TruthLog::record(std::uint64_t tick, const EntityStore& store) {
  if (file_ == nullptr) return;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (!dr::truthSampled(store.id[i].value, every_)) continue;
    const Vec3& p = store.pos[i];
    std::fprintf(file_, "%llu,%llu,%d,%.4f,%.4f,%.4f\n", static_cast<unsigned long long>(tick),
                 static_cast<unsigned long long>(store.id[i].value), int(store.kind[i]), p.x(),
                 p.y(), p.z());
  }
}

}  // namespace zonesim::zone
