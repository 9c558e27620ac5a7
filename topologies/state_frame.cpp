#include "topologies/state_frame.h"

#include <stdexcept>

#include "wire/downlink_frame.h"

namespace zonesim::topo {

std::vector<std::uint8_t> encodeStateFrame(const dr::StateCodec& codec, std::uint64_t token,
                                           std::uint32_t seq, std::uint64_t tick,
                                           std::span<const dr::WireEntity> entities) {
  std::vector<dr::PackedChunk> chunks = codec.pack(entities, tick, gateway::kMaxFramePayloadBytes);
  if (chunks.size() != 1)
    throw std::invalid_argument("encodeStateFrame: " + std::to_string(entities.size()) +
                                " entities do not fit one datagram");
  gateway::FrameHeader h{gateway::FrameKind::StateBatch, seq, tick, chunks[0].count};
  return gateway::encodeFrame(h, chunks[0].bytes, token);
}

DecodedStates decodeStateFrame(const dr::StateCodec& codec, std::span<const std::uint8_t> bytes,
                               std::uint64_t token) {
  DecodedStates out;
  gateway::ParsedFrame parsed = gateway::parseFrame(bytes, token);
  if (!parsed.ok()) {
    out.drop = parsed.drop;
    return out;
  }
  if (parsed.frame.header.kind != gateway::FrameKind::StateBatch) {
    out.drop = gateway::DropReason::UnexpectedType;
    return out;
  }
  out.tick = parsed.frame.header.tick;
  auto entities = codec.unpack(parsed.frame.payload, parsed.frame.header.count, out.tick);
  if (!entities) {
    out.drop = gateway::DropReason::OutOfRange;
    return out;
  }
  out.entities = std::move(*entities);
  return out;
}

}  // namespace zonesim::topo
