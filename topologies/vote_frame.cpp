#include "topologies/vote_frame.h"

#include "topologies/keyed_frame.h"
#include "wire/leb128.h"

namespace zonesim::topo {

namespace {

constexpr std::size_t kSuspectsBytes = 8;

}  // namespace

std::vector<std::uint8_t> encodeVote(const Vote& vote, std::uint64_t token) {
  std::vector<std::uint8_t> out{kVoteTag};
  frame::appendU32(out, vote.voter);
  gateway::appendLeb128(out, vote.tick);
  for (std::size_t i = 0; i < kSuspectsBytes; ++i)
    out.push_back(std::uint8_t(vote.suspects >> (8 * i)));
  frame::appendKeyedCrc(out, token);
  return out;
}

ParsedVote parseVote(std::span<const std::uint8_t> bytes, std::uint64_t token) {
  using gateway::DropReason;
  constexpr std::size_t kMin = 1 + 4 + 1 + kSuspectsBytes + 4;
  if (bytes.size() > gateway::kMaxDatagramBytes) return {{}, DropReason::TooLarge};
  if (bytes.size() < kMin) return {{}, DropReason::Truncated};
  if (bytes[0] != kVoteTag) return {{}, DropReason::BadIdentifier};
  if (!frame::keyedCrcMatches(bytes, token)) return {{}, DropReason::BadChecksum};
  std::span<const std::uint8_t> body = bytes.first(bytes.size() - 4);
  ParsedVote out;
  out.vote.voter = frame::readU32(body, 1);
  std::size_t at = 5;
  auto tick = gateway::readLeb128(body, at);
  if (!tick || body.size() - at != kSuspectsBytes) return {{}, DropReason::Malformed};
  out.vote.tick = *tick;
  for (std::size_t i = 0; i < kSuspectsBytes; ++i)
    out.vote.suspects |= Suspects(body[at + i]) << (8 * i);
  if (out.vote.voter >= 64 || (out.vote.suspects & suspectBit(out.vote.voter)))
    return {{}, DropReason::OutOfRange};
  return out;
}

}  // namespace zonesim::topo
