// What a node does with the datagrams of the game: states, hit claims and inputs, each
// checked for who may send it before what it says is judged.
#include "topologies/state_frame.h"
#include "topologies/topology_node.h"
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
      drop(gateway::DropReason::OutOfRange, sender);
      continue;
    }
    if (checks() &&
        checker_.checkState(player, e.tick, e.state.pos, e.state.vel) != Violation::None)
      continue;
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
  if (config_.role != Role::Client && h.hit.attacker != *sender)
    return drop(gateway::DropReason::OutOfRange, sender);
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
  if (checks() && checker_.checkHit(h.hit.attacker, *a, *b) != Violation::None) return;
  ++hits_accepted_;
  if (config_.role == Role::Host) {
    std::vector<std::uint8_t> report = encodeHit(h.hit, config_.token);
    for (const gateway::Endpoint& to : receivers()) send(to, report);
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

}  // namespace zonesim::topo
