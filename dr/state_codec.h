#pragma once
// Quantised entity states for the client protocol, and the packing of many of them into one
// bit stream. Position is relative to the entity's interest cell (so its size depends on the
// cell size, not the world), orientation is smallest-three, velocity, acceleration and angular
// velocity are bounded ranges; each field's bit count follows from range / resolution.
//
// The zone quantises what it sends and keeps the dequantised state as its dead-reckoning
// reference, the gateway re-quantises the zone's floats to the same integers, and the client
// dequantises them: all three hold the very same model state. Every parameter is a float, so
// the zone (scene doubles) and the client (Welcome floats) derive the same steps.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "dr/bit_stream.h"
#include "dr/dr_model.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::dr {

/// Everything both ends need to agree on; sent in the Welcome.
struct CodecParams {
  float world_min[3] = {0, 0, 0}, world_max[3] = {1000, 100, 1000};
  float cell_size = 50;
  float position_resolution = 1.0f / 512;
  float max_speed = 64, velocity_resolution = 1.0f / 128;
  float max_acceleration = 64, acceleration_resolution = 1.0f / 32;
  float max_angular_velocity = 32, angular_velocity_resolution = 1.0f / 256;
  std::uint8_t rotation_bits = 10;
};

/// The codec parameters of a scene.
CodecParams codecParams(const Scene& scene);

/// One entity as it travels to clients: identity, the model and the state it was sampled with.
struct WireEntity {
  std::uint64_t id = 0;
  std::uint8_t kind = 0;
  std::uint64_t tick = 0;  ///< zone tick the state was sampled at
  int cell = 0;            ///< interest cell the position is relative to
  Model model;
  State state;
  /// Smallest-three component to drop, 0..3; -1: the largest. A state decoded once and sent
  /// on as floats keeps its index, so a near tie cannot flip it on the way.
  int rot_largest = -1;
};

/// A record's state part (kind, model, cell, position, velocity, acceleration, orientation and
/// angular velocity: everything after its id and tick), quantised once. The gateway encodes
/// each entity's state once a tick and shares it across every player it goes to; per
/// datagram only the id and tick prefixes are written (they are deltas within the stream).
struct EncodedState {
  static constexpr int kMaxBits = 512;
  std::uint64_t words[kMaxBits / 64] = {};
  int bits = 0;
  /// Appends the low n bits of v (n in 0..64; the codec keeps the total within kMaxBits).
  void write(std::uint64_t v, int n) {
    if (n == 0) return;
    if (n < 64) v &= (std::uint64_t{1} << n) - 1;
    int word = bits / 64, off = bits % 64;
    words[word] |= v << off;
    if (off + n > 64) words[word + 1] |= v >> (64 - off);
    bits += n;
  }
};

/// A record's state bits by what they carry: what the entity is (kind and model), where it is
/// (cell and position), how it moves (velocity, acceleration) and how it is turned
/// (orientation, angular velocity).
struct FieldBits {
  int descriptor = 0, position = 0, velocity = 0, orientation = 0;
  int total() const { return descriptor + position + velocity + orientation; }
};

/// Bits BitWriter::writeVar takes for v: a 7-bit width, then the width's bits.
constexpr int varBits(std::uint64_t v) {
  return 7 + (v == 0 ? 0 : 64 - __builtin_clzll(v));
}

/// An entity ready to pack from its encoded state (which must outlive it).
struct EncodedEntity {
  std::uint64_t id = 0;
  std::uint64_t tick = 0;  ///< zone tick the state was sampled at
  const EncodedState* state = nullptr;
};

/// One uniform quantiser over [lo, lo + steps * resolution].
struct Quantiser {
  double lo = 0, resolution = 1;
  int bits = 1;
  std::uint64_t encode(double v) const;
  double decode(std::uint64_t q) const { return lo + double(q) * resolution; }
  /// Largest code (2^bits - 1).
  std::uint64_t maxCode() const { return (std::uint64_t{1} << bits) - 1; }
};

/// One packed stream and how many entities it holds.
struct PackedChunk {
  std::vector<std::uint8_t> bytes;
  std::size_t count = 0;
};

class StateCodec {
 public:
  explicit StateCodec(const CodecParams& p);

  /// The state a receiver decodes for s relative to `cell` (quantise, then dequantise); the
  /// smallest-three index used goes to *largest if given.
  State roundTrip(const State& s, const Model& m, int cell, int* largest = nullptr) const;
  /// Appends one entity; prev_id is the id written before it in this stream (0 at the start).
  void write(BitWriter& w, const WireEntity& e, std::uint64_t prev_id,
             std::uint64_t batch_tick) const;
  /// The state part of e's record, as write() writes it after the id and tick.
  EncodedState encodeState(const WireEntity& e) const;
  /// Appends one entity from its encoded state: the very bits write() gives the same entity.
  void write(BitWriter& w, const EncodedEntity& e, std::uint64_t prev_id,
             std::uint64_t batch_tick) const;
  /// Reads one entity; nullopt on a malformed or out-of-range record.
  std::optional<WireEntity> read(BitReader& r, std::uint64_t prev_id,
                                 std::uint64_t batch_tick) const;

  /// Packs entities (ascending ids) into streams of at most max_bytes each.
  std::vector<PackedChunk> pack(std::span<const WireEntity> entities, std::uint64_t batch_tick,
                                std::size_t max_bytes) const;
  /// The same streams into chunks[0..n), returning n: chunks only grows, and each chunk's
  /// bytes keep their storage, so a caller that keeps `chunks` allocates nothing once it
  /// has grown. From encoded states, the same streams as from the entities they encode.
  std::size_t packInto(std::span<const WireEntity> entities, std::uint64_t batch_tick,
                       std::size_t max_bytes, std::vector<PackedChunk>& chunks) const;
  std::size_t packInto(std::span<const EncodedEntity> entities, std::uint64_t batch_tick,
                       std::size_t max_bytes, std::vector<PackedChunk>& chunks) const;
  /// Unpacks `count` entities; nullopt if anything is wrong (overrun, range, order, leftovers).
  std::optional<std::vector<WireEntity>> unpack(std::span<const std::uint8_t> bytes,
                                                std::size_t count, std::uint64_t batch_tick) const;

  int cellCount() const { return columns_ * rows_; }
  int columns() const { return columns_; }
  /// Bits of a record without the id and tick prefixes, for the given model.
  int stateBits(const Model& m) const;
  /// The same bits by what they say (a bandwidth profile's field groups).
  FieldBits fieldBits(const Model& m) const;
  /// The field bits of an encoded state (its model read back from its first bits).
  FieldBits fieldBits(const EncodedState& s) const;
  const CodecParams& params() const { return params_; }
  /// Orientation component step (smallest-three).
  double rotationStep() const { return rot_.resolution; }

 private:
  Quantiser horizontal(int index_along, double world_min) const;

  CodecParams params_;
  int columns_ = 1, rows_ = 1, cell_bits_ = 0;
  Quantiser px_, py_, vel_, acc_, rot_, angvel_;
};

/// Smallest-three: index of the dropped component (the largest unless forced: force >= 0) and
/// the other three, signs flipped so that the dropped one is positive.
void smallestThree(const Q4& q, int& largest, double (&rest)[3], int force = -1);
/// The inverse of smallestThree.
Q4 fromSmallestThree(int largest, const double (&rest)[3]);

}  // namespace zonesim::dr
