#pragma once
// Entity records <-> FlatBuffers (idl/entity_record.fbs), for migration and state gathering.
// Decoding verifies the buffer first: a record from another rank is still checked.

#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// An input that reached this zone after its avatar left; travels with the next migration.
struct ForwardedInput {
  std::uint64_t player_id = 0;
  std::uint32_t seq = 0;
  float move_x = 0, move_z = 0;
};

/// The contents of one MigrationBatch.
struct MigrationPayload {
  std::uint64_t tick = 0;
  int from_rank = -1;
  std::vector<EntityRecordData> entities;
  std::vector<ForwardedInput> inputs;
};

class CodecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Alignment at which a batch is read in place: its widest scalar is a double. The FlatBuffers
/// Verifier checks alignment relative to the buffer's start only, not the address.
inline constexpr std::size_t kBatchAlign = alignof(double);

/// Serialises a batch into bytes (a finished FlatBuffer with file identifier "ZSER").
std::vector<std::uint8_t> encodeMigration(const MigrationPayload& payload);
/// Verifies and decodes a batch; throws CodecError on a malformed buffer. bytes may start at any
/// address (a segment of a gathered buffer): a misaligned one is copied before it is read.
MigrationPayload decodeMigration(std::span<const std::uint8_t> bytes);

}  // namespace zonesim::zone
