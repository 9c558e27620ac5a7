#pragma once
// zone_node --record DIR: DIR/zone_<rank>.zsrec, one frame per tick (idl/recording.fbs): the
// zone's entities and ghosts (all, or the ids the sampling keeps), its rectangle, its
// handoffs, rebalances, checkpoints and restart, and the tick's phase and stage times. The
// frame is built in kept buffers and written with one flushed write: no allocation per tick
// once the buffers have grown, and a live inspector sees each tick as it ends.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace flatbuffers {
class FlatBufferBuilder;
}

namespace zonesim {
struct Scene;
}

namespace zonesim::recording {
class RecordingWriter;
struct EntitySample;
struct Event;
}  // namespace zonesim::recording

namespace zonesim::zone {

class ZoneNode;

/// Whether entity id `id` is recorded when one id in `every` is (1: all).
bool recordedId(std::uint64_t id, std::uint32_t every);

class ZoneRecorder {
 public:
  /// Opens dir/zone_<rank>.zsrec and writes its Header; `every`: record one entity id in
  /// every (1: all). Throws std::runtime_error naming the file if it cannot be written.
  ZoneRecorder(const std::string& dir, const Scene& scene, const ZoneNode& node,
               std::uint32_t every, bool restarted);
  ~ZoneRecorder();
  ZoneRecorder(const ZoneRecorder&) = delete;
  ZoneRecorder& operator=(const ZoneRecorder&) = delete;

  /// Records the tick the node just ran (`tick_seconds`: its wall time).
  void record(const ZoneNode& node, double tick_seconds);
  /// Writes the index and closes the file.
  void close();

 private:
  std::unique_ptr<recording::RecordingWriter> writer_;
  std::unique_ptr<flatbuffers::FlatBufferBuilder> fbb_;
  std::uint32_t every_;
  double dt_;  // simulated seconds per tick (time dilation stretches the period, not dt)
  std::uint64_t last_checkpoint_;
  bool restart_pending_;  // the first frame says where the zone began
  std::vector<recording::EntitySample> entities_;
  std::vector<recording::Event> events_;
  std::vector<float> phase_ms_, stage_ms_;
};

}  // namespace zonesim::zone
