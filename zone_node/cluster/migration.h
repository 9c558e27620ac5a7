#pragma once
// Ownership transfer: every tick, entities whose position lies in another rank's zone are packed
// (FlatBuffers), sent, removed here and added there, exactly once. Counts go first with
// MPI_Alltoall, payloads with MPI_Alltoallv (LAMMPS' exchange(), with one collective).

#include <mpi.h>

#include <cstdint>
#include <vector>

#include "zone_node/cluster/byte_exchange.h"
#include "zone_node/cluster/entity_codec.h"
#include "zone_node/departure.h"
#include "zone_node/entity_store.h"
#include "zone_node/zone_layout.h"

namespace zonesim::zone {

/// An entity that arrived during the exchange.
struct Arrival {
  std::size_t index;  ///< its index in the store right after the exchange
  int from_rank;
  EntityId id;
};

struct MigrationResult {
  std::vector<Departure> departed;
  std::vector<Arrival> arrived;
  std::vector<ForwardedInput> inputs;  ///< inputs other ranks forwarded to us
  std::uint64_t bytes_sent = 0;
};

class Migrator {
 public:
  Migrator(MPI_Comm comm, int rank, int size);

  /// Moves leavers to their owners; `forward[r]` are inputs to pass to rank r with them.
  MigrationResult exchange(EntityStore& store, const ZoneLayout& layout, std::uint64_t tick,
                           std::vector<std::vector<ForwardedInput>>& forward);

 private:
  int rank_, size_;
  ByteExchange bytes_;
};

}  // namespace zonesim::zone
