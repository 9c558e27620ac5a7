#pragma once
// The ant colonies' trail deposits of a tick summed over every rank: each rank's ants lay trail
// on a grid that every rank holds whole (zone_node/systems/ant_movement.h). The deposits are
// fixed-point integers, so one MPI_Allreduce(SUM) gives every rank exactly the same total
// whatever the number of ranks and the order of the sum.

#include <mpi.h>

#include <cstdint>
#include <span>

namespace zonesim::zone {

/// Replaces `deltas` on every rank of `comm` by its element-wise sum over all ranks.
/// Collective: every rank must call it with the same length.
void sumTrailDeltas(MPI_Comm comm, std::span<std::int64_t> deltas);

}  // namespace zonesim::zone
