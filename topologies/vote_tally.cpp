#include "topologies/vote_tally.h"

#include <stdexcept>
#include <string>

namespace zonesim::topo {

void Verdict::caught(std::uint32_t player, std::uint64_t tick) {
  std::uint64_t& last = last_caught_[player];
  if (tick > last) last = tick;
}

Suspects Verdict::at(std::uint64_t now) const {
  Suspects out = 0;
  for (const auto& [player, tick] : last_caught_)
    if (tick <= now && now - tick < hold_ticks_ && player < 64) out |= suspectBit(player);
  return out;
}

VoteTally::VoteTally(std::uint32_t players, std::uint64_t ttl_ticks)
    : players_(players), ttl_ticks_(ttl_ticks), votes_(players) {
  if (players == 0 || players > 64)
    throw std::invalid_argument("a vote tally is for 1 to 64 players, not " +
                                std::to_string(players));
}

bool VoteTally::record(const Vote& vote) {
  if (vote.voter >= players_) return false;
  Held& held = votes_[vote.voter];
  if (held.known && vote.tick <= held.vote.tick) return false;
  held = {true, vote};
  return true;
}

std::uint32_t VoteTally::votesAgainst(std::uint32_t player, std::uint64_t now) const {
  if (player >= players_) return 0;
  std::uint32_t n = 0;
  for (std::uint32_t voter = 0; voter < players_; ++voter) {
    const Held& h = votes_[voter];
    bool counts = h.known && voter != player && h.vote.tick + ttl_ticks_ >= now;
    n += counts && (h.vote.suspects & suspectBit(player)) != 0;
  }
  return n;
}

}  // namespace zonesim::topo
