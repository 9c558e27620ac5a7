#include "gateway/gateway_recorder.h"

#include <flatbuffers/flatbuffers.h>

#include "common/interest_grid.h"
#include "common/scene.h"
#include "recorder/recording_file.h"
#include "recording_generated.h"
#include "wire/leb128.h"

namespace zonesim::gateway {

namespace rec = zonesim::recording;

namespace {

constexpr std::uint32_t kHeaderVersion = 1;
constexpr std::size_t kFrameTrailerBytes = 4;  // the keyed CRC-32C
constexpr std::size_t kFrameFixedBytes = 1 + 4;  // tag and seq, before the tick

std::size_t group(FieldGroup g) { return std::size_t(g); }

}  // namespace

GatewayRecorder::GatewayRecorder(const std::string& dir, int index, const Scene& scene,
                                 const InterestGrid& grid, const dr::StateCodec& codec)
    : writer_(std::make_unique<rec::RecordingWriter>(dir + "/gateway_" + std::to_string(index) +
                                                     ".zsrec")),
      fbb_(std::make_unique<flatbuffers::FlatBufferBuilder>(1 << 16)),
      codec_(codec) {
  flatbuffers::FlatBufferBuilder& b = *fbb_;
  rec::Rect world(float(scene.world.min.x), float(scene.world.min.z), float(scene.world.max.x),
                  float(scene.world.max.z));
  const std::vector<std::string> groups{"position", "orientation", "velocity", "lifecycle",
                                        "headers"};
  auto header = rec::CreateHeader(
      b, kHeaderVersion, rec::ProcessKind::Gateway, index, b.CreateString(scene.name), &world,
      scene.dt, scene.world.min.x, scene.world.min.z, grid.cell_size(), grid.columns(),
      grid.rows(), 0, 0, b.CreateVectorOfStrings(groups), 1, 0, 0);
  rec::FinishRecordBuffer(b, rec::CreateRecord(b, rec::Frame::Header, header.Union()));
  writer_->write(b, 0, /*indexed=*/false);
}

GatewayRecorder::~GatewayRecorder() = default;

void GatewayRecorder::frameBits(Player& p, const std::vector<std::uint8_t>& frame,
                                std::uint64_t payload_bits) {
  // The frame's own layout: tag and seq, LEB128 tick and count, payload, trailer.
  std::size_t at = kFrameFixedBytes;
  const std::span<const std::uint8_t> bytes(frame);
  const bool parsed = readLeb128(bytes, at).has_value() && readLeb128(bytes, at).has_value() &&
                      at + kFrameTrailerBytes <= frame.size();
  const std::uint64_t payload_bytes = parsed ? frame.size() - at - kFrameTrailerBytes : 0;
  const std::uint64_t padding = payload_bytes * 8 - payload_bits;
  if (!parsed || payload_bytes * 8 < payload_bits || padding >= 8) ++frames_mismatched_;
  // Whatever the model got wrong lands in headers, so the groups still hold the frame's bytes.
  p.bits[group(FieldGroup::Headers)] += frame.size() * 8 - payload_bits;
}

void GatewayRecorder::stateFrames(std::uint64_t player,
                                  std::span<const std::vector<std::uint8_t>> frames,
                                  std::span<const std::size_t> counts,
                                  std::span<const dr::EncodedEntity> states,
                                  std::uint64_t batch_tick, bool spawns) {
  Player& p = players_[player];
  std::size_t k = 0;
  for (std::size_t f = 0; f < counts.size() && f < frames.size(); ++f) {
    std::uint64_t prev = 0, payload_bits = 0;
    for (std::size_t n = 0; n < counts[f]; ++n, ++k) {
      const dr::EncodedEntity& e = states[k];
      const dr::FieldBits fields = codec_.fieldBits(*e.state);
      const int prefix = dr::varBits(e.id - prev) + dr::varBits(batch_tick - e.tick);
      prev = e.id;
      p.bits[group(FieldGroup::Position)] += std::uint64_t(fields.position);
      p.bits[group(FieldGroup::Orientation)] += std::uint64_t(fields.orientation);
      p.bits[group(FieldGroup::Velocity)] += std::uint64_t(fields.velocity);
      // A spawn's descriptor says what appears; an update's repeats it (headers).
      p.bits[group(spawns ? FieldGroup::Lifecycle : FieldGroup::Headers)] +=
          std::uint64_t(fields.descriptor);
      p.bits[group(FieldGroup::Headers)] += std::uint64_t(prefix);
      const std::uint64_t record = std::uint64_t(fields.total() + prefix);
      p.entity_bits[e.id] += record;
      payload_bits += record;
    }
    frameBits(p, frames[f], payload_bits);
  }
}

void GatewayRecorder::despawnFrames(std::uint64_t player,
                                    std::span<const std::vector<std::uint8_t>> frames,
                                    std::span<const std::size_t> counts,
                                    std::span<const std::uint64_t> ids) {
  Player& p = players_[player];
  std::size_t k = 0;
  for (std::size_t f = 0; f < counts.size() && f < frames.size(); ++f) {
    std::uint64_t prev = 0, payload_bits = 0;
    for (std::size_t n = 0; n < counts[f]; ++n, ++k) {
      const std::uint64_t bits = 8 * leb128Size(ids[k] - prev);
      prev = ids[k];
      p.bits[group(FieldGroup::Lifecycle)] += bits;
      p.entity_bits[ids[k]] += bits;
      payload_bits += bits;
    }
    frameBits(p, frames[f], payload_bits);
  }
}

void GatewayRecorder::controlDatagram(std::uint64_t player, std::size_t bytes) {
  players_[player].bits[group(FieldGroup::Headers)] += 8 * bytes;
}

void GatewayRecorder::view(std::uint64_t player, std::uint64_t avatar, double x, double z,
                           double nimbus, std::span<const RecordedVisible> visible,
                           std::uint64_t socket_bytes_total) {
  Player& p = players_[player];
  if (!p.seen) {
    // Bytes sent before the first view (the Welcome) belong to no frame: start counting here.
    p.seen = true;
    p.socket_bytes_at_frame = socket_bytes_total;
    p.bits = {};
    p.entity_bits.clear();
  }
  p.viewed = true;
  p.avatar = avatar;
  p.x = float(x);
  p.z = float(z);
  p.nimbus = float(nimbus);
  p.socket_bytes = socket_bytes_total;
  p.visible.assign(visible.begin(), visible.end());
}

void GatewayRecorder::epoch(std::uint32_t epoch) { events_epoch_.push_back({0, epoch}); }

void GatewayRecorder::endTick(std::uint64_t tick, double sim_time,
                              std::span<const std::pair<int, int>> cells) {
  flatbuffers::FlatBufferBuilder& b = *fbb_;
  b.Clear();
  std::vector<flatbuffers::Offset<rec::PlayerFrame>> frames;
  std::vector<rec::VisibleSample> visible;
  std::vector<rec::EntityBytes> entity_bytes;
  std::vector<std::uint32_t> field_bytes(kFieldGroupCount);
  for (auto& [id, p] : players_) {
    if (!p.viewed) continue;
    p.viewed = false;
    visible.clear();
    for (const RecordedVisible& v : p.visible)
      visible.emplace_back(v.id, v.x, v.z, v.kind, rec::VisibleReason(v.reason));
    entity_bytes.clear();
    for (const auto& [entity, bits] : p.entity_bits)
      entity_bytes.emplace_back(entity, std::uint32_t((bits + 7) / 8));
    // Whole bytes per group; the odd bits carry to the next frame, so totals never drift.
    for (std::size_t g = 0; g < kFieldGroupCount; ++g) {
      field_bytes[g] = std::uint32_t(p.bits[g] / 8);
      p.bits[g] %= 8;
    }
    const std::uint32_t socket = std::uint32_t(p.socket_bytes - p.socket_bytes_at_frame);
    frames.push_back(rec::CreatePlayerFrame(
        b, id, p.avatar, p.x, p.z, p.nimbus, b.CreateVectorOfStructs(visible), socket,
        b.CreateVector(field_bytes), b.CreateVectorOfStructs(entity_bytes)));
    p.socket_bytes_at_frame = p.socket_bytes;
    p.entity_bits.clear();
  }
  std::vector<rec::CellSubscribers> subscribed;
  for (const auto& [cell, players] : cells)
    subscribed.emplace_back(std::uint32_t(cell), std::uint16_t(std::min(players, 65535)));
  std::vector<rec::Event> events;
  for (const auto& [entity, e] : events_epoch_)
    events.emplace_back(entity, e, int(e), rec::EventKind::Epoch);
  events_epoch_.clear();
  auto frame = rec::CreateGatewayTick(b, tick, sim_time, b.CreateVectorOfStructs(subscribed),
                                      b.CreateVector(frames), b.CreateVectorOfStructs(events));
  rec::FinishRecordBuffer(b, rec::CreateRecord(b, rec::Frame::GatewayTick, frame.Union()));
  writer_->write(b, tick);
}

void GatewayRecorder::close() { writer_->close(); }

}  // namespace zonesim::gateway
