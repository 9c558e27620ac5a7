#pragma once
// --dump-state: every entity's final state, gathered to rank 0 and written one JSON object per
// line in id order, so dumps from runs with different rank counts compare line by line; then
// every live particle (they have no ids: sorted by their state, so equal dumps mean equal
// particle sets).

#include <mpi.h>

#include <array>
#include <string>
#include <vector>

#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// Collective: all ranks call it; rank 0 writes the file. Throws on I/O failure.
void dumpState(MPI_Comm comm, const EntityStore& store,
               const std::vector<std::array<double, 6>>& particles, const std::string& path);

}  // namespace zonesim::zone
