#pragma once
// Builds client-protocol datagrams: FlatBuffers Datagrams, except StateBatch, Spawn and Despawn,
// which go as lean frames (wire/downlink_frame.h). Lists of entities are split into chunks so
// that every datagram stays within kMaxDatagramBytes and nothing is lost between chunks.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "client_protocol_generated.h"
#include "dr/state_codec.h"
#include "wire/downlink_frame.h"
#include "wire/input_history.h"
#include "wire/wire_verify.h"

namespace zonesim::gateway {

/// One encoded datagram.
using Bytes = std::vector<std::uint8_t>;

/// Packed state bytes per StateBatch or Spawn datagram: what a lean frame (wire/downlink_frame.h)
/// always has room for.
inline constexpr std::size_t kPackedBytesPerDatagram = kMaxFramePayloadBytes;

/// World bounds and rates announced in a Welcome.
struct WelcomeInfo {
  std::uint64_t client_nonce = 0;
  std::uint64_t token = 0;
  std::uint64_t player_id = 0;
  std::uint64_t avatar_id = 0;
  int zone = 0;
  float tick_rate = 30;
  proto::Vec3f world_min, world_max;
  dr::CodecParams codec;
  float sim_dt = 1.0f / 30;
  std::vector<std::uint8_t> resume_token;  ///< auth/resume_token.h; empty: none
  std::uint32_t last_input_seq = 0;        ///< the last input the avatar's zone applied
};

/// The wire form of codec parameters, and back.
proto::CodecParams toProto(const dr::CodecParams& c);
dr::CodecParams fromProto(const proto::CodecParams& c);

/// Handoff notice fields.
struct HandoffInfo {
  std::uint64_t avatar_id = 0;
  int from_zone = -1;
  int to_zone = 0;
  std::uint64_t tick = 0;
  std::uint32_t last_input_seq = 0;
  std::uint32_t seq = 0;  ///< the session's datagram seq (0: unnumbered)
};

/// One transaction of a player's reliable channel (the Transaction table).
struct TransactionInfo {
  std::uint32_t seq = 0;
  std::uint8_t kind = 0;  ///< ledger::Kind
  std::uint64_t item = 0;
  std::int64_t amount = 0;
  std::uint64_t counterparty = 0;
  std::int64_t price = 0;
  std::int64_t score = 0;
  /// The client's acknowledgement point: every transaction up to it has its outcome.
  std::uint32_t decided = 0;
  bool operator==(const TransactionInfo&) const = default;
};

/// The fields of a verified Transaction.
TransactionInfo transactionInfo(const proto::Transaction& t);

/// connect_token: the lobby's token, opaque here (empty: none, for a gateway without a key);
/// kind: the player's kind id (common/player_kind.h); resume_token: an earlier Welcome's, to come
/// back as the same player after a gateway died (empty: a new player).
Bytes encodeHello(std::uint64_t client_nonce, std::string_view name,
                  std::span<const std::uint8_t> connect_token = {}, std::uint8_t kind = 0,
                  std::span<const std::uint8_t> resume_token = {});
/// ack / ack_bits: the client's acknowledgement of gateway datagrams (wire/ack_window.h);
/// earlier: the inputs just before this one, oldest first, sent again (none: not written).
Bytes encodeInput(std::uint64_t token, std::uint32_t seq, float move_x, float move_z,
                  std::uint32_t ack = 0, std::uint32_t ack_bits = 0,
                  std::span<const InputRecord> earlier = {});
/// ack / ack_bits as in encodeInput.
Bytes encodePing(std::uint64_t token, std::uint64_t client_time_us, std::uint32_t ack = 0,
                 std::uint32_t ack_bits = 0);
Bytes encodeBye(std::uint64_t token);
Bytes encodeTransaction(std::uint64_t token, const TransactionInfo& t);
/// count: 1 .. kMaxLeaderboardRows.
Bytes encodeLeaderboardQuery(std::uint64_t token, std::uint8_t count);
/// One row of a Leaderboard.
struct LeaderboardLine {
  std::uint64_t player = 0;
  std::int64_t score = 0;
  std::uint64_t tick = 0;
  bool operator==(const LeaderboardLine&) const = default;
};
/// At most kMaxLeaderboardRows of `rows`; reason (cut to kMaxReasonBytes): why it could not be
/// read ("" if it was).
Bytes encodeLeaderboard(std::uint64_t token, std::span<const LeaderboardLine> rows,
                        std::string_view reason);
/// status: ledger::TxStatus; reason is cut to kMaxReasonBytes.
Bytes encodeTransactionOutcome(std::uint64_t token, std::uint32_t seq, std::uint8_t status,
                               std::string_view reason);
/// The Datagram's token is the new session token too, so the client can check it.
Bytes encodeWelcome(const WelcomeInfo& w);
Bytes encodePong(std::uint64_t token, std::uint64_t client_time_us, std::uint64_t gateway_time_us,
                 float dilation = 1.0f);
Bytes encodeHandoff(std::uint64_t token, const HandoffInfo& h);
/// A StateBatch frame with no states: tells a client whose view is quiet that the zones' clock
/// moved on (unnumbered: nothing in it needs resending).
Bytes encodeClockTick(std::uint64_t token, std::uint64_t tick);

/// Sequence numbering of a run of chunks: chunk i gets seq next() (0 = unnumbered), and
/// counts (if given) receives how many entities each chunk holds.
struct ChunkSeq {
  std::uint32_t (*next)(void*) = nullptr;
  void* ctx = nullptr;
  std::vector<std::size_t>* counts = nullptr;
  std::uint32_t take() const { return next != nullptr ? next(ctx) : 0; }
};

/// Numbering for measuring only: every chunk gets a seq of the width a real one has, so the
/// frames are exactly as large as the ones later sent with the session's own seqs.
inline ChunkSeq sizingSeq() {
  return {[](void*) { return std::uint32_t{0xffffffff}; }, nullptr, nullptr};
}
/// Bytes of a run of encoded chunks together.
inline std::size_t totalBytes(const std::vector<Bytes>& chunks) {
  std::size_t n = 0;
  for (const Bytes& b : chunks) n += b.size();
  return n;
}

/// StateBatch frames carrying all states (ascending ids), packed by the codec, in order.
std::vector<Bytes> encodeStateChunks(std::uint64_t token, std::uint64_t tick,
                                     const dr::StateCodec& codec,
                                     std::span<const dr::WireEntity> states, ChunkSeq seq = {});
/// Spawn frames carrying all states (ascending ids), packed by the codec, in order.
std::vector<Bytes> encodeSpawnChunks(std::uint64_t token, std::uint64_t tick,
                                     const dr::StateCodec& codec,
                                     std::span<const dr::WireEntity> states, ChunkSeq seq = {});
/// Buffers the frame encoders below reuse: chunks and frames keep their storage between calls.
struct FrameScratch {
  std::vector<dr::PackedChunk> chunks;
  std::vector<Bytes> frames;
  Bytes payload;
};
/// As encodeStateChunks, encodeSpawnChunks and encodeDespawnChunks, the frames into
/// scratch.frames[0..n), returning n: nothing is allocated once the scratch has grown to a
/// run's size (the gateway's per-player sends).
std::size_t encodeStateFrames(std::uint64_t token, std::uint64_t tick, const dr::StateCodec& codec,
                              std::span<const dr::EncodedEntity> states, ChunkSeq seq,
                              FrameScratch& scratch);
std::size_t encodeSpawnFrames(std::uint64_t token, std::uint64_t tick, const dr::StateCodec& codec,
                              std::span<const dr::EncodedEntity> states, ChunkSeq seq,
                              FrameScratch& scratch);
std::size_t encodeDespawnFrames(std::uint64_t token, std::uint64_t tick,
                                std::span<const std::uint64_t> ids, ChunkSeq seq,
                                FrameScratch& scratch);
/// Bytes of frames[0..n) together.
inline std::size_t totalBytes(const FrameScratch& scratch, std::size_t n) {
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < n; ++i) bytes += scratch.frames[i].size();
  return bytes;
}
/// Despawn frames carrying all ids (strictly ascending: std::invalid_argument otherwise), as
/// many per frame as fit, in order.
std::vector<Bytes> encodeDespawnChunks(std::uint64_t token, std::uint64_t tick,
                                       std::span<const std::uint64_t> ids, ChunkSeq seq = {});

}  // namespace zonesim::gateway
