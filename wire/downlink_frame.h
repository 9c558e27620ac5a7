#pragma once
// The lean downlink frame. StateBatch, Spawn and Despawn are most of what a gateway sends, a few
// records (~150 bits each) per datagram, so the framing around them is what a client pays for:
// 80 bytes as a FlatBuffers Datagram (tables, vtables, vector headers, the 8-byte token),
// 13 here (a server up 9 minutes to 19 hours, under 128 records). These three travel in this
// fixed little-endian layout; every other message stays a FlatBuffers Datagram
// (idl/client_protocol.fbs).
//
//   offset  bytes  field
//   0       1      tag: 0xA0 | kind (1 StateBatch, 2 Spawn, 3 Despawn); the high nibble is
//                  the layout version, its high bit what tells the frame from FlatBuffers
//   1       4      seq, u32 (0: unnumbered, the clock tick)
//   5       1-10   server tick, LEB128 (at 30 Hz 3 bytes from 9 minutes on, 4 from 19 hours,
//                  5 from 103 days)
//   ..      1-2    count: records or ids, LEB128, < 2^14
//   ..      n      payload: StateCodec::pack's bit stream (StateBatch, Spawn), or each id's
//                  LEB128 delta from the one before it, from 0, ascending (Despawn)
//   end-4   4      CRC-32C of the session token (8 bytes) and then bytes [0, end-4)
//
// The token does not travel: it is the key of the checksum (Glenn Fiedler's protocol id in the
// CRC), so a frame checks only for the session it was made for, and an off-path forger, who
// never saw the Welcome, cannot make one. A FlatBuffers datagram of ours begins with its root
// offset, which is small (< 0x80: the encoder checks it), so byte 0 alone tells the two apart.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "wire/drop_reason.h"

namespace zonesim::gateway {

/// What a lean frame carries.
enum class FrameKind : std::uint8_t { StateBatch = 1, Spawn = 2, Despawn = 3 };

/// Byte 0 of a frame is kFrameTag | kind: layout version 1.
inline constexpr std::uint8_t kFrameTag = 0xA0;
/// The smallest frame: tag, seq, one-byte tick and count, nothing packed, the trailer.
inline constexpr std::size_t kMinFrameBytes = 1 + 4 + 1 + 1 + 4;
/// The largest framing: a 10-byte tick and a 2-byte count.
inline constexpr std::size_t kMaxFrameOverheadBytes = 1 + 4 + 10 + 2 + 4;
/// Payload that always fits in one datagram, whatever the tick and count.
inline constexpr std::size_t kMaxFramePayloadBytes = kMaxDatagramBytes - kMaxFrameOverheadBytes;
/// Counts take at most two LEB128 bytes; a datagram holds far fewer records (20 bits at least).
inline constexpr std::size_t kMaxFrameCount = (std::size_t{1} << 14) - 1;
/// The smallest packed record (dr/state_codec.h), so at most 8 records per 20 payload bits.
inline constexpr std::size_t kMinRecordBits = 20;

/// True if byte 0 marks a lean frame rather than a FlatBuffers datagram.
inline bool isDownlinkFrame(std::span<const std::uint8_t> bytes) {
  return !bytes.empty() && (bytes[0] & 0x80) != 0;
}

/// The fields before the payload.
struct FrameHeader {
  FrameKind kind = FrameKind::StateBatch;
  std::uint32_t seq = 0;
  std::uint64_t tick = 0;
  std::size_t count = 0;
};

/// One frame for the session with this token. Throws std::invalid_argument if it would exceed
/// kMaxDatagramBytes or the count kMaxFrameCount (a caller's bug, not the network's).
std::vector<std::uint8_t> encodeFrame(const FrameHeader& h, std::span<const std::uint8_t> payload,
                                      std::uint64_t token);
/// The same frame into out (cleared first; its storage is kept, so a caller that reuses out
/// allocates nothing once it has grown).
void encodeFrameInto(const FrameHeader& h, std::span<const std::uint8_t> payload,
                     std::uint64_t token, std::vector<std::uint8_t>& out);

/// Appends id to a Despawn payload whose last id is prev (0 at the start); false, the payload
/// unchanged, if it would grow past max_bytes. Throws std::invalid_argument unless id > prev.
bool appendDespawnId(std::vector<std::uint8_t>& payload, std::uint64_t prev, std::uint64_t id,
                     std::size_t max_bytes);

/// A frame that passed every check.
struct DownlinkFrame {
  FrameHeader header;
  std::span<const std::uint8_t> payload;  ///< aliases the datagram
  std::vector<std::uint64_t> ids;         ///< a Despawn's ids, ascending
};

/// A checked frame, or why it was dropped.
struct ParsedFrame {
  DownlinkFrame frame;
  std::optional<DropReason> drop;
  bool ok() const { return !drop; }
};

/// Checks a frame for the session with this token (0: no Welcome yet), in order: size
/// (too_large, truncated), tag (bad_identifier), token known (not_ready), the keyed checksum
/// (bad_checksum: corrupted on the way, or not made with this token), the header's numbers
/// (malformed), the count against the payload (out_of_range: 20 bits a record, an empty
/// StateBatch only when nothing is packed, a Spawn or Despawn never empty) and a Despawn's ids
/// (out_of_range unless ascending and exactly filling the payload). Packed states are checked
/// as they are unpacked (StateCodec::unpack).
ParsedFrame parseFrame(std::span<const std::uint8_t> bytes, std::uint64_t token);

}  // namespace zonesim::gateway
