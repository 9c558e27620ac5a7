#pragma once
// gateway --record DIR: DIR/gateway_<id>.zsrec, one frame per gateway tick (idl/recording.fbs):
// the interest cells it subscribes to with their subscriber counts, and for each player its
// avatar, nimbus, visible set (why each entity is in it, where the stream shows it) and the
// bytes it was sent, by field group and by entity.
//
// Bandwidth attribution is bit accounting of each lean frame (wire/downlink_frame.h) as it
// goes out: a record's state bits by StateCodec::fieldBits, its id and age prefixes, the
// frame's own header and checksum and the padding of its last byte; every other datagram to a
// player (clock, handoff, welcome, pong, outcomes) counts as headers whole. The groups add up
// to the bytes the socket was handed for that player; a frame whose bits do not match its
// size (padding outside 0..7 bits) is counted in frames_mismatched(), which must stay 0.

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "dr/state_codec.h"

namespace flatbuffers {
class FlatBufferBuilder;
}

namespace zonesim {
struct Scene;
class InterestGrid;
}  // namespace zonesim

namespace zonesim::recording {
class RecordingWriter;
struct VisibleSample;
}  // namespace zonesim::recording

namespace zonesim::gateway {

/// The field groups of a player's downlink, in the recording's Header.field_groups order.
enum class FieldGroup { Position, Orientation, Velocity, Lifecycle, Headers, Count };
inline constexpr std::size_t kFieldGroupCount = std::size_t(FieldGroup::Count);

/// One entity of a player's visible set, as the recorder takes it.
struct RecordedVisible {
  std::uint64_t id;
  float x, z;            // where the stream shows it now
  std::uint8_t kind;
  std::uint8_t reason;   // recording::VisibleReason
};

class GatewayRecorder {
 public:
  /// Opens dir/gateway_<index>.zsrec and writes its Header; throws std::runtime_error naming the
  /// file if it cannot.
  GatewayRecorder(const std::string& dir, int index, const Scene& scene, const InterestGrid& grid,
                  const dr::StateCodec& codec);
  ~GatewayRecorder();
  GatewayRecorder(const GatewayRecorder&) = delete;
  GatewayRecorder& operator=(const GatewayRecorder&) = delete;

  /// Lean StateBatch or Spawn frames just sent to a player: frames[i] holds counts[i] of
  /// `states` in order, packed against batch_tick.
  void stateFrames(std::uint64_t player, std::span<const std::vector<std::uint8_t>> frames,
                   std::span<const std::size_t> counts, std::span<const dr::EncodedEntity> states,
                   std::uint64_t batch_tick, bool spawns);
  /// Lean Despawn frames just sent: frames[i] holds counts[i] of `ids` in order.
  void despawnFrames(std::uint64_t player, std::span<const std::vector<std::uint8_t>> frames,
                     std::span<const std::size_t> counts, std::span<const std::uint64_t> ids);
  /// Any other datagram to a player (counted as headers whole).
  void controlDatagram(std::uint64_t player, std::size_t bytes);
  /// A player's view at a recorded tick; socket_bytes_total: all bytes ever sent to it (its
  /// frame holds the bytes since its previous frame).
  void view(std::uint64_t player, std::uint64_t avatar, double x, double z, double nimbus,
            std::span<const RecordedVisible> visible, std::uint64_t socket_bytes_total);
  /// Writes a frame: the views given since the last call, the cells with subscribers.
  void endTick(std::uint64_t tick, double sim_time, std::span<const std::pair<int, int>> cells);
  /// A new cluster epoch's samples arrived.
  void epoch(std::uint32_t epoch);
  /// Writes the index and closes the file.
  void close();

  /// Frames whose bits did not add up to their size (the attribution's model is wrong).
  std::uint64_t framesMismatched() const { return frames_mismatched_; }

 private:
  struct Player {
    std::array<std::uint64_t, kFieldGroupCount> bits{};  // since its last frame
    std::map<std::uint64_t, std::uint64_t> entity_bits;  // the same, entity-attributable part
    std::uint64_t socket_bytes_at_frame = 0;
    bool seen = false;
    bool viewed = false;  // a view this tick
    std::uint64_t avatar = 0;
    float x = 0, z = 0, nimbus = 0;
    std::uint64_t socket_bytes = 0;
    std::vector<RecordedVisible> visible;
  };
  /// Bits of a frame's header and trailer, and the bytes of its payload.
  void frameBits(Player& p, const std::vector<std::uint8_t>& frame, std::uint64_t payload_bits);

  std::unique_ptr<recording::RecordingWriter> writer_;
  std::unique_ptr<flatbuffers::FlatBufferBuilder> fbb_;
  const dr::StateCodec& codec_;
  std::map<std::uint64_t, Player> players_;  // by player id: frames list them in that order
  std::vector<std::pair<std::uint64_t, std::uint32_t>> events_epoch_;
  std::uint64_t frames_mismatched_ = 0;
};

}  // namespace zonesim::gateway
