#include "zone_node/cluster/conservation.h"

#include <cstdint>

namespace zonesim::zone {

ConservationReport checkConservation(MPI_Comm comm, const EntityStore& store,
                                     const IdSetDigest& ledger) {
  IdSetDigest local;
  for (EntityId id : store.id) local.add(id);
  // Unsigned sums wrap modulo 2^64 on every rank alike, so the hash stays order-independent.
  std::uint64_t in[4] = {local.count, local.hash, ledger.count, ledger.hash};
  std::uint64_t out[4] = {};
  MPI_Allreduce(in, out, 4, MPI_UINT64_T, MPI_SUM, comm);
  ConservationReport r;
  r.actual = {out[0], out[1]};
  r.expected = {out[2], out[3]};
  return r;
}

}  // namespace zonesim::zone
