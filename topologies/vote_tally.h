#pragma once
// Majority voting among peers (docs/networking.md, "Topologies"). Each peer holds a verdict:
// the players it caught lying (a state or hit its plausibility checker rejected, a frame in
// another player's name) within the last hold_ticks, so a player that plays honestly again is
// forgiven by itself. Peers send their verdicts to each other; each keeps every voter's newest
// one, and a vote counts for ttl_ticks after the tick it carries, so the verdict of a voter
// that left or whose withdrawal was lost lapses. A player is excluded while more than half of
// the other players of the game vote against it: the denominator is the game's size, not the
// voters heard, so a lying minority cannot exclude anyone however many honest votes are lost.
// No I/O: the node feeds it and the tests drive it tick by tick.

#include <cstdint>
#include <map>
#include <vector>

#include "topologies/vote_frame.h"

namespace zonesim::topo {

/// This peer's own verdict.
class Verdict {
 public:
  explicit Verdict(std::uint64_t hold_ticks) : hold_ticks_(hold_ticks) {}
  /// player was caught lying at tick.
  void caught(std::uint32_t player, std::uint64_t tick);
  /// Those caught within hold_ticks before now (now included).
  Suspects at(std::uint64_t now) const;

 private:
  std::uint64_t hold_ticks_;
  std::map<std::uint32_t, std::uint64_t> last_caught_;  // by player: the newest tick
};

class VoteTally {
 public:
  /// players in the game (1..64); a vote counts until ttl_ticks after its tick.
  VoteTally(std::uint32_t players, std::uint64_t ttl_ticks);
  /// Keeps voter's vote if it is newer than the last one recorded from voter; false (ignored)
  /// if it is not, or if the voter is not a player of the game.
  bool record(const Vote& vote);
  /// Voters other than player whose vote counts at now and names player.
  std::uint32_t votesAgainst(std::uint32_t player, std::uint64_t now) const;
  /// Votes needed to exclude a player: a majority of the others, (players - 1) / 2 + 1. With
  /// fewer than three players the one other's vote cannot tell a liar from its accuser, so no
  /// count excludes anyone (players: more votes than there are others); each peer still drops
  /// the states its own checker rejects.
  std::uint32_t needed() const { return players_ < 3 ? players_ : (players_ - 1) / 2 + 1; }
  /// Whether the others' votes at now exclude player.
  bool excluded(std::uint32_t player, std::uint64_t now) const {
    return votesAgainst(player, now) >= needed();
  }

 private:
  struct Held {
    bool known = false;
    Vote vote;
  };
  std::uint32_t players_;
  std::uint64_t ttl_ticks_;
  std::vector<Held> votes_;  // by voter
};

}  // namespace zonesim::topo
