#include "wire/wire_encode.h"

#include <algorithm>
#include <cassert>
#include <stdexcept>

#include "wire/datagram_checksum.h"

namespace zonesim::gateway {

namespace {

template <typename T>
Bytes finish(flatbuffers::FlatBufferBuilder& fbb, std::uint64_t token, proto::Message type,
             flatbuffers::Offset<T> msg) {
  auto root = proto::CreateDatagram(fbb, token, type, msg.Union());
  proto::FinishDatagramBuffer(fbb, root);
  Bytes out;
  out.reserve(fbb.GetSize() + kChecksumBytes);
  out.assign(fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize());
  appendChecksum(out);
  assert(out.size() <= kMaxDatagramBytes);
  // Byte 0 is the low byte of the root offset, just past the identifier and the root's vtable:
  // were it ever 0x80 or more, the client would take the datagram for a lean frame.
  if (isDownlinkFrame(out)) throw std::logic_error("FlatBuffers datagram starts like a frame");
  return out;
}

}  // namespace

namespace {
// No bytes, no field: a Hello or Welcome without a token is the same bytes as before tokens
// existed.
flatbuffers::Offset<flatbuffers::Vector<std::uint8_t>> optionalBytes(
    flatbuffers::FlatBufferBuilder& fbb, std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return {};
  return fbb.CreateVector(bytes.data(), bytes.size());
}
}  // namespace

Bytes encodeHello(std::uint64_t client_nonce, std::string_view name,
                  std::span<const std::uint8_t> connect_token, std::uint8_t kind,
                  std::span<const std::uint8_t> resume_token) {
  flatbuffers::FlatBufferBuilder fbb(128 + connect_token.size() + resume_token.size());
  auto t = optionalBytes(fbb, connect_token);
  auto r = optionalBytes(fbb, resume_token);
  auto n = fbb.CreateString(name.data(), name.size());
  // A walker's kind, the default 0, is not written either.
  return finish(fbb, 0, proto::Message::Hello,
                proto::CreateHello(fbb, client_nonce, n, t, kind, r));
}

Bytes encodeInput(std::uint64_t token, std::uint32_t seq, float move_x, float move_z,
                  std::uint32_t ack, std::uint32_t ack_bits, std::span<const InputRecord> earlier) {
  flatbuffers::FlatBufferBuilder fbb(96 + 12 * earlier.size());
  flatbuffers::Offset<flatbuffers::Vector<const proto::InputMove*>> moves;
  if (!earlier.empty()) {
    proto::InputMove* out = nullptr;
    moves = fbb.CreateUninitializedVectorOfStructs(earlier.size(), &out);
    for (const InputRecord& e : earlier) *out++ = proto::InputMove(e.seq, e.move_x, e.move_z);
  }
  return finish(fbb, token, proto::Message::Input,
                proto::CreateInput(fbb, seq, move_x, move_z, ack, ack_bits, moves));
}

Bytes encodePing(std::uint64_t token, std::uint64_t client_time_us, std::uint32_t ack,
                 std::uint32_t ack_bits) {
  flatbuffers::FlatBufferBuilder fbb(96);
  return finish(fbb, token, proto::Message::Ping,
                proto::CreatePing(fbb, client_time_us, ack, ack_bits));
}

Bytes encodeBye(std::uint64_t token) {
  flatbuffers::FlatBufferBuilder fbb(64);
  return finish(fbb, token, proto::Message::Bye, proto::CreateBye(fbb));
}

TransactionInfo transactionInfo(const proto::Transaction& t) {
  return {t.seq(),   t.kind(),  t.item(), t.amount(), t.counterparty(),
          t.price(), t.score(), t.decided()};
}

Bytes encodeTransaction(std::uint64_t token, const TransactionInfo& t) {
  flatbuffers::FlatBufferBuilder fbb(128);
  auto msg = proto::CreateTransaction(fbb, t.seq, t.kind, t.item, t.amount, t.counterparty,
                                      t.price, t.score, t.decided);
  return finish(fbb, token, proto::Message::Transaction, msg);
}

Bytes encodeLeaderboardQuery(std::uint64_t token, std::uint8_t count) {
  flatbuffers::FlatBufferBuilder fbb(64);
  return finish(fbb, token, proto::Message::LeaderboardQuery,
                proto::CreateLeaderboardQuery(fbb, count));
}

Bytes encodeLeaderboard(std::uint64_t token, std::span<const LeaderboardLine> rows,
                        std::string_view reason) {
  rows = rows.first(std::min(rows.size(), kMaxLeaderboardRows));
  flatbuffers::FlatBufferBuilder fbb(96 + 24 * rows.size() + reason.size());
  proto::LeaderboardEntry* out = nullptr;
  auto entries = fbb.CreateUninitializedVectorOfStructs(rows.size(), &out);
  for (const LeaderboardLine& r : rows) *out++ = proto::LeaderboardEntry(r.player, r.score, r.tick);
  auto text = reason.empty() ? flatbuffers::Offset<flatbuffers::String>()
                             : fbb.CreateString(reason.substr(0, kMaxReasonBytes));
  return finish(fbb, token, proto::Message::Leaderboard,
                proto::CreateLeaderboard(fbb, entries, text));
}

Bytes encodeTransactionOutcome(std::uint64_t token, std::uint32_t seq, std::uint8_t status,
                               std::string_view reason) {
  flatbuffers::FlatBufferBuilder fbb(96 + reason.size());
  auto text = fbb.CreateString(reason.substr(0, kMaxReasonBytes));
  auto msg = proto::CreateTransactionOutcome(fbb, seq, status, text);
  return finish(fbb, token, proto::Message::TransactionOutcome, msg);
}

proto::CodecParams toProto(const dr::CodecParams& c) {
  return proto::CodecParams(proto::Vec3f(c.world_min[0], c.world_min[1], c.world_min[2]),
                            proto::Vec3f(c.world_max[0], c.world_max[1], c.world_max[2]),
                            c.cell_size, c.position_resolution, c.max_speed, c.velocity_resolution,
                            c.max_acceleration, c.acceleration_resolution, c.max_angular_velocity,
                            c.angular_velocity_resolution, c.rotation_bits);
}

dr::CodecParams fromProto(const proto::CodecParams& c) {
  dr::CodecParams p;
  p.world_min[0] = c.world_min().x(), p.world_min[1] = c.world_min().y();
  p.world_min[2] = c.world_min().z();
  p.world_max[0] = c.world_max().x(), p.world_max[1] = c.world_max().y();
  p.world_max[2] = c.world_max().z();
  p.cell_size = c.cell_size();
  p.position_resolution = c.position_resolution();
  p.max_speed = c.max_speed();
  p.velocity_resolution = c.velocity_resolution();
  p.max_acceleration = c.max_acceleration();
  p.acceleration_resolution = c.acceleration_resolution();
  p.max_angular_velocity = c.max_angular_velocity();
  p.angular_velocity_resolution = c.angular_velocity_resolution();
  p.rotation_bits = c.rotation_bits();
  return p;
}

Bytes encodeWelcome(const WelcomeInfo& w) {
  flatbuffers::FlatBufferBuilder fbb(256 + w.resume_token.size());
  proto::CodecParams codec = toProto(w.codec);
  auto r = optionalBytes(fbb, w.resume_token);
  auto msg = proto::CreateWelcome(fbb, w.client_nonce, w.token, w.player_id, w.avatar_id, w.zone,
                                  w.tick_rate, &w.world_min, &w.world_max, &codec, w.sim_dt, r,
                                  w.last_input_seq);
  return finish(fbb, w.token, proto::Message::Welcome, msg);
}

Bytes encodePong(std::uint64_t token, std::uint64_t client_time_us, std::uint64_t gateway_time_us,
                 float dilation) {
  flatbuffers::FlatBufferBuilder fbb(96);
  return finish(fbb, token, proto::Message::Pong,
                proto::CreatePong(fbb, client_time_us, gateway_time_us, dilation));
}

Bytes encodeHandoff(std::uint64_t token, const HandoffInfo& h) {
  flatbuffers::FlatBufferBuilder fbb(128);
  auto msg = proto::CreateHandoff(fbb, h.avatar_id, h.from_zone, h.to_zone, h.tick,
                                  h.last_input_seq, h.seq);
  return finish(fbb, token, proto::Message::Handoff, msg);
}

Bytes encodeClockTick(std::uint64_t token, std::uint64_t tick) {
  return encodeFrame({FrameKind::StateBatch, 0, tick, 0}, {}, token);
}

namespace {
/// One frame slot of the scratch, grown as needed.
Bytes& frameAt(FrameScratch& scratch, std::size_t i) {
  if (i == scratch.frames.size()) scratch.frames.emplace_back();
  return scratch.frames[i];
}

template <typename Entity>
std::size_t packedFrames(FrameKind kind, std::uint64_t token, std::uint64_t tick,
                         const dr::StateCodec& codec, std::span<const Entity> states,
                         const ChunkSeq& seq, FrameScratch& scratch) {
  std::size_t n = codec.packInto(states, tick, kPackedBytesPerDatagram, scratch.chunks);
  for (std::size_t i = 0; i < n; ++i) {
    const dr::PackedChunk& c = scratch.chunks[i];
    encodeFrameInto({kind, seq.take(), tick, c.count}, c.bytes, token, frameAt(scratch, i));
    if (seq.counts != nullptr) seq.counts->push_back(c.count);
  }
  return n;
}

/// The first n frames of a scratch of its own, as a list.
std::vector<Bytes> firstFrames(FrameScratch& scratch, std::size_t n) {
  scratch.frames.resize(n);
  return std::move(scratch.frames);
}
}  // namespace

std::vector<Bytes> encodeStateChunks(std::uint64_t token, std::uint64_t tick,
                                     const dr::StateCodec& codec,
                                     std::span<const dr::WireEntity> states, ChunkSeq seq) {
  FrameScratch s;
  return firstFrames(s, packedFrames(FrameKind::StateBatch, token, tick, codec, states, seq, s));
}

std::vector<Bytes> encodeSpawnChunks(std::uint64_t token, std::uint64_t tick,
                                     const dr::StateCodec& codec,
                                     std::span<const dr::WireEntity> states, ChunkSeq seq) {
  FrameScratch s;
  return firstFrames(s, packedFrames(FrameKind::Spawn, token, tick, codec, states, seq, s));
}

std::size_t encodeStateFrames(std::uint64_t token, std::uint64_t tick, const dr::StateCodec& codec,
                              std::span<const dr::EncodedEntity> states, ChunkSeq seq,
                              FrameScratch& scratch) {
  return packedFrames(FrameKind::StateBatch, token, tick, codec, states, seq, scratch);
}

std::size_t encodeSpawnFrames(std::uint64_t token, std::uint64_t tick, const dr::StateCodec& codec,
                              std::span<const dr::EncodedEntity> states, ChunkSeq seq,
                              FrameScratch& scratch) {
  return packedFrames(FrameKind::Spawn, token, tick, codec, states, seq, scratch);
}

std::size_t encodeDespawnFrames(std::uint64_t token, std::uint64_t tick,
                                std::span<const std::uint64_t> ids, ChunkSeq seq,
                                FrameScratch& scratch) {
  std::size_t n = 0, count = 0;
  Bytes& payload = scratch.payload;
  payload.clear();
  auto close = [&] {
    encodeFrameInto({FrameKind::Despawn, seq.take(), tick, count}, payload, token,
                    frameAt(scratch, n++));
    if (seq.counts != nullptr) seq.counts->push_back(count);
    payload.clear();
    count = 0;
  };
  std::uint64_t prev = 0;
  for (std::uint64_t id : ids) {
    // Each frame's deltas start from 0 again, so that it reads alone.
    if (!appendDespawnId(payload, count > 0 ? prev : 0, id, kMaxFramePayloadBytes)) {
      close();
      appendDespawnId(payload, 0, id, kMaxFramePayloadBytes);
    }
    ++count;
    prev = id;
  }
  if (count > 0) close();
  return n;
}

std::vector<Bytes> encodeDespawnChunks(std::uint64_t token, std::uint64_t tick,
                                       std::span<const std::uint64_t> ids, ChunkSeq seq) {
  FrameScratch s;
  return firstFrames(s, encodeDespawnFrames(token, tick, ids, seq, s));
}

}  // namespace zonesim::gateway
