#pragma once
// --dump-state: every entity's final state, gathered to rank 0 and written one JSON object per
// line in id order, so dumps from runs with different rank counts compare line by line.

#include <mpi.h>

#include <string>

#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// Collective: all ranks call it; rank 0 writes the file. Throws on I/O failure.
void dumpState(MPI_Comm comm, const EntityStore& store, const std::string& path);

}  // namespace zonesim::zone
