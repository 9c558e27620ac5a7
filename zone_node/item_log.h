#pragma once
// What became of the scene's unique items (interactions.items), one CSV line per event:
//   tick,event,id   with event "left" (taken, its decision checkpointed: clients saw it go)
//                   or "restored" (lying untaken in the checkpoint a restarted zone began from).
// An item that left in one job and is restored untaken by a later one would be an event shown
// and then retracted; tests/integration/fault_survival.py counts those (it must find none).
// Lines are flushed as written: a zone killed mid-run keeps what it told.

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "common/entity_id.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

class ItemLog {
 public:
  /// Opens path (truncating); throws if it cannot. An empty path: no file, calls do nothing.
  explicit ItemLog(const std::string& path);
  ~ItemLog();
  ItemLog(const ItemLog&) = delete;
  ItemLog& operator=(const ItemLog&) = delete;

  /// The untaken items of a zone that began from a checkpoint at `tick`.
  void restored(std::uint64_t tick, const EntityStore& store);
  /// Items that left the world in the tick just run.
  void left(std::uint64_t tick, const std::vector<EntityId>& items);

 private:
  void write(std::uint64_t tick, const char* event, EntityId id);
  std::FILE* file_ = nullptr;
};

}  // namespace zonesim::zone
