// What a node does with the datagrams of the game: states, hit claims, inputs and votes, each
// checked for who may send it before what it says is judged. A peer keeps judging a player the
// vote excluded (so that its verdict can lapse when the player plays honestly again), but shows
// it nowhere and applies none of its hits nor any on it.
#include "topologies/node_rules.h"
#include "topologies/state_frame.h"
#include "topologies/topology_node.h"
#include "topologies/vote_frame.h"
#include "wire/wire_verify.h"

namespace zonesim::topo {

void TopologyNode::handleStates(std::span<const std::uint8_t> bytes,
                                std::optional<std::uint32_t> sender) {
  // States come from the host to its clients, and from every peer to every peer.
  bool expected = config_.role == Role::Peer ||
                  (config_.role == Role::Client && directory_.at(*sender).role == Role::Host);
  if (!expected) return drop(gateway::DropReason::UnexpectedType, sender);
  DecodedStates d = decodeStateFrame(codec_, bytes, config_.token);
  if (d.drop) return drop(*d.drop, sender);
  for (const dr::WireEntity& e : d.entities) {
    std::uint32_t player = playerOf(e.id);
    if (player == config_.player && config_.role == Role::Peer) continue;
    // A peer speaks for its own avatar only.
    if (config_.role == Role::Peer && player != *sender) {
      caught(*sender);
      drop(gateway::DropReason::OutOfRange, sender);
      continue;
    }
    if (checks()) {
      Violation v = checker_.checkState(player, e.tick, e.state.pos, e.state.vel);
      if (v != Violation::None && v != Violation::StaleTick) caught(player);
      if (v != Violation::None) continue;
    }
    states_of_excluded_ += excluded(player);
    show(player, e.tick, e.state);
  }
}

void TopologyNode::handleHit(std::span<const std::uint8_t> bytes,
                             std::optional<std::uint32_t> sender) {
  if (config_.role == Role::Client && directory_.at(*sender).role != Role::Host)
    return drop(gateway::DropReason::UnexpectedType, sender);
  ParsedHit h = parseHit(bytes, config_.token);
  if (h.drop) return drop(*h.drop, sender);
  // A claim speaks for its sender, except the host's reports of the hits it applied.
  if (config_.role != Role::Client && h.hit.attacker != *sender) {
    caught(*sender);
    return drop(gateway::DropReason::OutOfRange, sender);
  }
  std::optional<dr::V3> a = shownAt(h.hit.attacker, h.hit.tick),
                        b = shownAt(h.hit.target, h.hit.tick);
  if (!a || !b) return drop(gateway::DropReason::NotReady, sender);
  // A judge that no longer believes where the target is, or heard of either player too long
  // before the hit (a loaded machine's late states), cannot tell whether it was in reach. An
  // attacker it distrusts is judged where it was last believed: a hit from there is refused.
  bool unknowable = checker_.distrusts(h.hit.target) || staleAt(h.hit.target, h.hit.tick) ||
                    (!checker_.distrusts(h.hit.attacker) && staleAt(h.hit.attacker, h.hit.tick));
  if (checks() && unknowable) {
    ++hits_unjudged_;
    return;
  }
  if (checks() && checker_.checkHit(h.hit.attacker, *a, *b) != Violation::None)
    return caught(h.hit.attacker);
  if (excluded(h.hit.attacker) || excluded(h.hit.target)) {
    ++hits_of_excluded_;
    return;
  }
  ++hits_accepted_;
  if (config_.role == Role::Host) {
    std::vector<std::uint8_t> report = encodeHit(h.hit, config_.token);
    for (const Registration* r : recipients()) send(r->address, report);
  }
}

void TopologyNode::handleInput(std::span<const std::uint8_t> bytes,
                               std::optional<std::uint32_t> sender) {
  // Inputs go to the host alone, and it checks them exactly as the gateway does.
  if (config_.role != Role::Host) return drop(gateway::DropReason::UnexpectedType, sender);
  gateway::Verified v = gateway::verifyDatagram(bytes, gateway::Direction::ToGateway);
  if (!v.ok()) return drop(v.reason, sender);
  if (v.datagram->token() != config_.token) return drop(gateway::DropReason::BadToken, sender);
  const proto::Input* in = v.datagram->msg_as_Input();
  if (in == nullptr) return drop(gateway::DropReason::UnexpectedType, sender);
  std::uint32_t& last = input_seqs_[*sender];
  if (in->seq() <= last) return drop(gateway::DropReason::StaleInput, sender);
  last = in->seq();
  moves_[*sender] = {in->move_x(), in->move_z()};
}

void TopologyNode::handleVote(std::span<const std::uint8_t> bytes,
                              std::optional<std::uint32_t> sender) {
  if (config_.role != Role::Peer) return drop(gateway::DropReason::UnexpectedType, sender);
  ParsedVote p = parseVote(bytes, config_.token);
  if (p.drop) return drop(*p.drop, sender);
  // A vote speaks for its sender, of the game's players: anything else is a lie.
  bool beyond = config_.players < 64 && (p.vote.suspects >> config_.players) != 0;
  if (p.vote.voter != *sender || beyond) {
    caught(*sender);
    return drop(gateway::DropReason::OutOfRange, sender);
  }
  // Ticks run from one start time; one far ahead would count long after its time.
  if (p.vote.tick > now_tick_ + rules::kVoteAheadTicks)
    return drop(gateway::DropReason::OutOfRange, sender);
  if (!tally_.record(p.vote)) {
    ++votes_stale_;  // overtaken on the way: the newer vote stands
    return;
  }
  ++votes_in_;
  if (p.vote.suspects) ++votes_against_by_voter_[p.vote.voter];
}

}  // namespace zonesim::topo
