#pragma once
// Nothing lost, nothing doubled: the global entity count and an order-independent hash of ids
// must equal what was created minus what was destroyed, summed over ranks (one allreduce).

#include <mpi.h>

#include "common/entity_id.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

struct ConservationReport {
  IdSetDigest actual;    ///< over all ranks' stores
  IdSetDigest expected;  ///< over all ranks' created-minus-destroyed ledgers
  bool ok() const { return actual == expected; }
};

/// Collective: every rank calls it with its store and its own ledger.
ConservationReport checkConservation(MPI_Comm comm, const EntityStore& store,
                                     const IdSetDigest& ledger);

}  // namespace zonesim::zone
