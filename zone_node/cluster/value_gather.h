#pragma once
// One list of values from every rank, concatenated in rank order, for per-tick decisions that
// every rank must take alike from everyone's small share: the cluster-wide path request budget
// (zone_node/systems/agent_navigation.h) gathers the keys of each zone's oldest requests, and
// crowd level of detail (player_positions.h) every zone's avatar positions. The root-only form
// collects end-of-run outputs (state_dump.h's particles, arrival_log.h's arrivals) on rank 0.

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

namespace zonesim::zone {

/// Every rank's `mine`, concatenated in rank order (MPI_Allgatherv). Collective: every rank of
/// `comm` must call it.
std::vector<std::uint64_t> gatherValues(MPI_Comm comm, const std::vector<std::uint64_t>& mine);
/// As above for doubles.
std::vector<double> gatherValues(MPI_Comm comm, const std::vector<double>& mine);

/// Every rank's `mine`, concatenated in rank order on rank 0 (MPI_Gatherv); empty on the other
/// ranks. Collective: every rank of `comm` must call it.
std::vector<std::uint64_t> gatherValuesToRoot(MPI_Comm comm, std::span<const std::uint64_t> mine);
/// As above for doubles.
std::vector<double> gatherValuesToRoot(MPI_Comm comm, std::span<const double> mine);

}  // namespace zonesim::zone
