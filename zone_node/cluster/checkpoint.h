#pragma once
// Checkpoints: every K ticks each rank writes its entities (FlatBuffers records, as in migration)
// to its own file; rank 0 then writes a manifest with every file's size and hash and the global
// id digest, and last of all points LATEST at it. Each file is written to a temporary name,
// synced and renamed, so a crash at any moment leaves either the previous complete checkpoint
// or a new complete one: a checkpoint without a manifest, or whose files disagree with it, is
// never used. Restart reads every file and keeps what the new layout gives each rank, so the
// rank count may change.

#include <mpi.h>

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "zone_node/entity_store.h"

namespace zonesim::zone {

class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Everything a restart needs: the tick, every entity, and each creator's id counter.
struct CheckpointImage {
  std::uint64_t tick = 0;
  int ranks = 0;
  std::vector<EntityRecordData> entities;
  std::map<std::uint32_t, std::uint64_t> id_counters;  ///< creator rank -> ids issued
  std::string path;                                    ///< the checkpoint folder read
};

/// Collective. Writes DIR/ckpt_<tick>/ (one file per rank, then MANIFEST.json) and DIR/LATEST.
/// ids_issued is this rank's id counter; inherited are the counters a restart read (creators
/// beyond today's rank count keep theirs, so no id is ever issued twice). Returns the
/// checkpoint folder. Throws on I/O errors.
std::string writeCheckpoint(MPI_Comm comm, const EntityStore& store, std::uint64_t tick,
                            std::uint64_t ids_issued,
                            const std::map<std::uint32_t, std::uint64_t>& inherited,
                            const std::string& dir);

/// Reads and verifies a checkpoint: `path` is a checkpoint folder, or a DIR with LATEST in it.
/// Throws CheckpointError naming what is missing or inconsistent.
CheckpointImage readCheckpoint(const std::string& path);

/// FNV-1a 64 of bytes: cheap corruption check for checkpoint files (not a security hash).
std::uint64_t fnv1a64(const std::uint8_t* data, std::size_t size);

}  // namespace zonesim::zone
