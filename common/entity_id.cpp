#include "common/entity_id.h"

namespace zonesim {

std::string toString(EntityId id) {
  return std::to_string(id.creatorRank()) + ":" + std::to_string(id.counter());
}

}  // namespace zonesim
