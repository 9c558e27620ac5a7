#pragma once
// One player of a topology run (docs/networking.md, "Topologies"): it registers with the
// discovery service, finds what its role needs (a client: the host; a peer: the other peers;
// the host: its clients), then plays ticks aligned to a start time every node shares.
//   host:   simulates every avatar from its clients' inputs (checked as the gateway checks
//           them) and its own script, judges hit claims, sends everyone all states each tick;
//   client: sends its input each tick, shows the host's states, and with --cross-check holds
//           the host's states and hits to the movement limits too;
//   peer:   simulates its own avatar, sends its state to every other peer each tick, and
//           holds every other peer's states and hits to the movement limits; peers vote on who
//           lied (topologies/vote_tally.h), and one a majority caught is excluded by all: still
//           judged, so that it can earn its way back, but neither shown nor hit nor hitting.

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <span>
#include <vector>

#include "common/scene.h"
#include "dr/state_codec.h"
#include "topologies/arena_motion.h"
#include "topologies/discovery_registry.h"
#include "topologies/hit_frame.h"
#include "topologies/node_config.h"
#include "topologies/node_log.h"
#include "topologies/plausibility.h"
#include "topologies/vote_tally.h"
#include "wire/drop_reason.h"
#include "wire/impairment.h"
#include "wire/udp_socket.h"

namespace zonesim::topo {

class TopologyNode {
 public:
  TopologyNode(const NodeConfig& config, const Scene& scene);
  /// Joins, plays config.duration_s, writes the summary. Throws std::runtime_error when the
  /// game cannot be joined (no host, too few peers) within the join timeout.
  void run();

 private:
  // What this node shows of a player: the newest accepted state and when it was sampled.
  struct Shown {
    std::uint64_t tick = 0;
    dr::State state;
    dr::V3 logged_vel;  // the velocity last written as "seen"
    bool known = false;
  };

  // discovery
  void registerSelf();
  void requestList();
  void handleDiscovery(std::span<const std::uint8_t> bytes);
  bool joined() const;
  void join();
  // the game
  void play();
  void receiveUntil(std::int64_t deadline_ns);
  void handle(std::span<const std::uint8_t> bytes, const gateway::Endpoint& from);
  void handleStates(std::span<const std::uint8_t> bytes, std::optional<std::uint32_t> sender);
  void handleHit(std::span<const std::uint8_t> bytes, std::optional<std::uint32_t> sender);
  void handleInput(std::span<const std::uint8_t> bytes, std::optional<std::uint32_t> sender);
  void handleVote(std::span<const std::uint8_t> bytes, std::optional<std::uint32_t> sender);
  void tick(std::uint64_t t);
  void stepOwn(std::uint64_t t, const Move& move);
  void sendStates(std::uint64_t t);
  void sendVote(std::uint64_t t);
  void cheatVote(std::uint64_t t);
  void tallyVotes(std::uint64_t t);
  void claimHits(std::uint64_t t);
  void cheatTeleport(std::uint64_t t);
  void logViews(std::uint64_t t);
  void writeSummary(double played_s) const;
  // helpers
  void send(const gateway::Endpoint& to, std::span<const std::uint8_t> bytes);
  void drop(gateway::DropReason reason, std::optional<std::uint32_t> sender);
  void show(std::uint32_t player, std::uint64_t t, const dr::State& s);
  std::optional<dr::V3> shownAt(std::uint32_t player, std::uint64_t t) const;
  /// Whether what this node last heard of player is too old to judge a hit at tick t by.
  bool staleAt(std::uint32_t player, std::uint64_t t) const;
  std::optional<std::uint32_t> playerAt(const gateway::Endpoint& from) const;
  /// A lie of player caught now: a claim the checker rejected, a frame in another's name.
  void caught(std::uint32_t player);
  /// Whether this node excludes player by the peers' vote.
  bool excluded(std::uint32_t player) const { return excluded_.count(player) != 0; }
  /// The others this node sends to, by player (the host: its clients; a client: its host).
  std::vector<const Registration*> recipients() const;
  bool checks() const { return config_.role != Role::Client || config_.cross_check; }
  double maxSpeed() const;

  NodeConfig config_;
  Cheats cheats_;  // what it fakes at this tick (config_.cheats until --cheat-seconds)
  const Scene& scene_;
  dr::StateCodec codec_;
  MovementLimits limits_;
  PlausibilityChecker checker_;
  ScriptedInput script_;
  gateway::UdpSocket socket_, discovery_socket_;
  gateway::Impairment link_;  // this player's access link, both ways (--link)
  NodeLog log_;

  std::map<std::uint32_t, Registration> directory_;  // from the discovery service, by player
  std::map<std::uint32_t, Shown> shown_;
  AvatarBody own_;
  // The host's game: every avatar, its newest input and that input's seq.
  std::map<std::uint32_t, AvatarBody> bodies_;
  std::map<std::uint32_t, Move> moves_;
  std::map<std::uint32_t, std::uint32_t> input_seqs_;
  std::uint32_t seq_ = 0;
  std::uint64_t now_tick_ = 0;
  // Voting among peers.
  Verdict verdict_;
  VoteTally tally_;
  bool voted_against_anyone_ = false;  // the last vote sent named someone
  std::set<std::uint32_t> excluded_;

  // counters for the summary
  std::uint64_t bytes_in_ = 0, bytes_out_ = 0, datagrams_in_ = 0, datagrams_out_ = 0;
  std::uint64_t hits_claimed_ = 0, hits_accepted_ = 0, hits_unjudged_ = 0;
  gateway::DropCounters drops_;
  std::map<std::uint32_t, std::uint64_t> drops_by_player_;
  std::uint64_t votes_sent_ = 0, votes_in_ = 0, votes_stale_ = 0;
  std::uint64_t states_of_excluded_ = 0, hits_of_excluded_ = 0;
  std::map<std::uint32_t, std::uint64_t> votes_against_by_voter_;  // accepted votes naming anyone
  std::map<std::uint32_t, std::uint64_t> excluded_since_;          // first tick each was excluded
  std::map<std::uint32_t, std::uint64_t> readmitted_at_;  // the last tick each was let back in
};

}  // namespace zonesim::topo
