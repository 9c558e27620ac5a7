#include "zone_node/item_log.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace zonesim::zone {

ItemLog::ItemLog(const std::string& path) {
  if (path.empty()) return;
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  std::fputs("tick,event,id\n", file_);
  std::fflush(file_);
}

ItemLog::~ItemLog() {
  if (file_) std::fclose(file_);
}

void ItemLog::write(std::uint64_t tick, const char* event, EntityId id) {
  std::fprintf(file_, "%llu,%s,%llu\n", (unsigned long long)tick, event,
               (unsigned long long)id.value);
}

void ItemLog::restored(std::uint64_t tick, const EntityStore& store) {
  if (!file_) return;
  for (std::size_t i = 0; i < store.size(); ++i)
    if (store.kind[i] == EntityKind::Item && store.combat[i].taken_at == 0)
      write(tick, "restored", store.id[i]);
  std::fflush(file_);
}

void ItemLog::left(std::uint64_t tick, const std::vector<EntityId>& items) {
  if (!file_ || items.empty()) return;
  for (EntityId id : items) write(tick, "left", id);
  std::fflush(file_);
}

}  // namespace zonesim::zone
