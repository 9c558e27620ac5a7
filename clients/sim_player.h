#pragma once
// One simulated player: its own UDP socket, the Hello/Welcome handshake (retried until
// answered), inputs at a fixed rate from the wander profile, a Ping a second for RTT, and a
// RemoteView fed by Spawn/StateBatch/Despawn (lean frames, checked with the session's token).
// Everything from the network is verified first: the client does not trust the gateway either.
// When the gateway falls silent, the player says Hello again with its Welcome's resume token,
// to the same gateway (restarted) or the next one it knows, and goes on as the same player with
// the same avatar: it resends the inputs after the last one the zone applied.

#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "clients/remote_view.h"
#include "clients/reservoir.h"
#include "clients/transaction_stream.h"
#include "clients/wander.h"
#include "common/scene_clients.h"
#include "common/scene_geometry.h"
#include "dr/state_codec.h"
#include "wire/ack_window.h"
#include "wire/datagram_batch.h"
#include "wire/downlink_frame.h"
#include "wire/impairment.h"
#include "wire/input_history.h"
#include "wire/udp_socket.h"
#include "wire/wire_encode.h"
#include "wire/wire_verify.h"

namespace zonesim::clients {

using gateway::DropCounters;
using gateway::Endpoint;

/// Settings shared by all players of one run.
struct PlayerConfig {
  Endpoint gateway;
  SceneBox world;
  double input_hz = 20;
  double retarget_seconds = 8;
  double hello_retry_s = 0.5;
  double ping_every_s = 1.0;
  std::uint64_t seed = 1;
  gateway::ImpairmentSettings impairment;  ///< the player's uplink (out) and downlink (in)
  bool blend = true;      ///< projective velocity blending of corrections; false: snap
  double blend_s = 0.25;  ///< blend time, seconds
  double stale_after_s =
      6;  ///< a known entity silent this long is counted a ghost (heartbeat + margin)
  std::uint32_t truth_every = 0;  ///< log what is shown of every k-th id each tick (0: none)
  /// The server-clock estimate runs at most this far (seconds) past the newest tick heard of,
  /// so that stalled zones freeze the view instead of flinging entities along their last
  /// motion; the gateway tells a quiet view the tick more often than this. 0: unbounded.
  double max_lead_s = 0.25;
  /// The lobby's connect token for `gateway`, carried in every Hello (empty: none, no lobby).
  std::vector<std::uint8_t> connect_token;
  /// The player's kind, said in the Hello; its speed sets how near a wander target counts as
  /// reached (the zone moves the avatar at it).
  PlayerKind kind;
  /// Nothing from the gateway for this long (seconds) means it is gone: resume elsewhere. The
  /// gateway sends a quiet view the clock several times a second. 0: never resume.
  double resume_after_s = 1.0;
  /// A resume not welcomed after this long (seconds) gives up: the player starts over as a
  /// new one (its avatar may have been removed, or the token expired).
  double resume_give_up_s = 10;
  /// Other gateways of the cluster to resume at, tried in turn after `gateway` (which may be
  /// restarted on its address).
  std::vector<Endpoint> fallback_gateways;
  /// Transactions (loot, purchases, scores) each player makes a second on its reliable
  /// channel (clients/transaction_stream.h); 0: none.
  double transactions_per_s = 0;
  /// Seconds between the player's leaderboard queries (0: it never asks).
  double leaderboard_every_s = 0;
  /// Earlier inputs each Input carries again (at most gateway::kMaxEarlierInputs; 0: none).
  std::uint32_t input_redundancy = 3;
};

/// Where a player showed a sampled entity (dr/truth_sample.h) at a server tick.
struct DisplaySample {
  std::uint64_t tick = 0, id = 0;
  dr::Order order = dr::Order::First;
  float x = 0, y = 0, z = 0;
  float distance = -1;  ///< planar, from the player's avatar as shown then; -1: not shown yet
};

/// One event of a player's own stream: a new state of its avatar arrived, or a Handoff notice.
struct OwnEvent {
  std::int64_t t_ns = 0;   ///< receive time (the fleet's clock)
  std::uint64_t tick = 0;  ///< the state's sample tick, or the handoff's crossing tick
  double server_tick = 0;  ///< the player's estimate of the server tick at receipt
  bool handoff = false;
};

/// What one player counted.
struct PlayerCounters {
  std::uint64_t datagrams_in = 0, bytes_in = 0, datagrams_out = 0, bytes_out = 0;
  std::uint64_t updates = 0, spawns = 0, despawns = 0, handoffs = 0, pongs = 0;
  std::uint64_t hellos = 0, inputs = 0, send_failures = 0;
  std::uint64_t duplicates = 0, stale_lifecycle = 0;  ///< datagrams seen twice; old spawn/despawn
  std::uint64_t repeats = 0;  ///< states or handoffs no newer than the ones held (resends)
  DropCounters drops;
  Reservoir rtt_ms;      ///< round trips, one per Pong
  Reservoir dr_error_m;  ///< correction seen at each update of a known entity
  double last_rtt_ms = 0;
  double min_dilation = 1;  ///< the slowest zone clock rate a Pong told of
  // Gateway faults (resume tokens):
  std::uint64_t resumes = 0;            ///< sessions resumed after the gateway fell silent
  std::uint64_t resume_failed = 0;      ///< resumes given up: started over as a new player
  std::uint64_t resume_new_avatar = 0;  ///< resumed with another avatar than before
  std::uint64_t inputs_resent = 0;      ///< inputs sent again after a resume
  std::uint64_t inputs_unresendable = 0;  ///< ones the zone lacked that were no longer kept
  Reservoir resume_s;  ///< from the last datagram heard to the resumed Welcome, seconds
  // The leaderboard (LeaderboardQuery -> Leaderboard):
  std::uint64_t leaderboard_queries = 0, leaderboards = 0;
  std::uint64_t leaderboards_unordered = 0;  ///< answers not best first (never, if all is well)
  std::uint64_t leaderboard_rows = 0;        ///< rows of the newest answer
  std::int64_t leaderboard_top = 0;          ///< its best score
};

class SimPlayer {
 public:
  /// index selects the player's nonce stream and wander generator; start_ns staggers its inputs.
  SimPlayer(const PlayerConfig& config, std::uint32_t index, std::int64_t start_ns);
  /// The same, playing from `socket`: the one the player logged in from, since its connect
  /// token names that socket's address and port (clients/lobby_login.h).
  SimPlayer(const PlayerConfig& config, std::uint32_t index, std::int64_t start_ns,
            gateway::UdpSocket socket);

  int fd() const { return socket_.fd(); }
  /// Sends whatever is due at now_ns; returns when it next has something to send.
  std::int64_t act(std::int64_t now_ns);
  /// Reads every pending datagram and handles it, or, with impairment, hands it to the
  /// player's downlink, which delivers it when due (act()).
  void receive(std::int64_t now_ns);
  /// The same, up to ReceiveBatch::kBatch datagrams per system call into `batch`: one batch
  /// serves a whole fleet (a batch's buffers per player would be 90 KB each).
  void receive(std::int64_t now_ns, gateway::ReceiveBatch& batch);
  /// Sends Bye if a session is open.
  void bye();
  /// Sends what the impaired uplink holds that is due by now_ns (a Bye, after the run); returns
  /// when the next held datagram is due (INT64_MAX: none).
  std::int64_t flushUplink(std::int64_t now_ns);

  bool welcomed() const { return token_ != 0; }
  /// The player's kind, as said in its Hello.
  PlayerKindId kind() const { return config_.kind.id; }
  /// Entities in view, averaged over the inputs sent (20 a second by default) since the Welcome.
  double meanVisible() const {
    return visible_samples_ > 0 ? visible_sum_ / double(visible_samples_) : 0.0;
  }
  /// Where the player shows its own avatar now (nothing before its first state).
  std::optional<Point3> ownPosition(std::int64_t now_ns) const {
    return view_.shown(avatar_id_, serverTick(now_ns));
  }
  std::uint64_t playerId() const { return player_id_; }
  std::uint64_t avatarId() const { return avatar_id_; }
  int zone() const { return zone_; }
  /// What the player's transaction channel did.
  const TransactionCounters& transactionCounters() const { return transactions_.counters(); }
  /// Transactions made and not decided yet.
  std::size_t pendingTransactions() const { return transactions_.pending(); }
  /// The gateway the player plays through now.
  const Endpoint& gateway() const { return knownGateway(gateway_index_); }
  /// Seconds from the first Hello to the Welcome (negative if none yet).
  double welcomeSeconds() const;
  const RemoteView& view() const { return view_; }
  const PlayerCounters& counters() const { return counters_; }
  const Wander& wander() const { return wander_; }
  /// Receipts of the avatar's own states and of Handoff notices, in arrival order (bounded).
  const std::vector<OwnEvent>& ownStream() const { return own_; }
  /// What was shown of the sampled entities, one sample per entity and server tick (bounded).
  const std::vector<DisplaySample>& displayed() const { return displayed_; }

  /// The estimated server tick at now_ns (fractional): the newest tick heard of, advanced by
  /// the wall time since at the announced tick rate times the zones' time dilation factor
  /// (from the Pongs), at most max_lead_s past it.
  double serverTick(std::int64_t now_ns) const;
  /// The zones' time dilation factor the newest Pong told (1: full speed).
  double dilation() const { return dilation_; }
  /// The codec announced in the Welcome (nullptr before).
  const dr::StateCodec* codec() const { return codec_ ? &*codec_ : nullptr; }

  /// Known entities with no state for stale_after_s: ghosts of lost despawns.
  std::size_t ghosts(std::int64_t now_ns) const;
  /// Entities the gateway keeps updating that the player was never spawned for (lost spawns),
  /// counted when updates kept coming for over a second without a Spawn.
  std::size_t unspawned() const;
  /// The acknowledgement window of gateway datagrams.
  const gateway::AckWindow& acks() const { return acks_; }
  /// The player's link impairment (its profiles and what they did).
  const gateway::Impairment& impairment() const { return impairment_; }

  /// Handles one datagram from `from` (public so tests can feed crafted bytes).
  void handle(std::span<const std::uint8_t> bytes, const Endpoint& from, std::int64_t now_ns);

 private:
  void send(const gateway::Bytes& bytes);
  /// Counts one datagram read from the socket and handles it or hands it to the downlink.
  void take(std::span<const std::uint8_t> bytes, const gateway::Received& got, std::int64_t now_ns);
  /// Handles the datagrams the impaired downlink releases by now_ns.
  void deliverHeld(std::int64_t now_ns);
  /// Sends what is due at now_ns (Hello, input, Ping, or a resume); returns when next.
  std::int64_t actDue(std::int64_t now_ns);
  /// Not welcomed yet: Hello (with the resume token while resuming, to the next gateway in
  /// turn), or give up resuming and come as a new player.
  std::int64_t helloDue(std::int64_t now_ns);
  void sendInput(std::int64_t now_ns);
  void onWelcome(const proto::Datagram& d, std::int64_t now_ns);
  /// The gateway fell silent: say Hello with the resume token from now on, to the next
  /// gateway in turn.
  void beginResume(std::int64_t now_ns);
  /// A resumed Welcome: a new session, so a new stream; resends what the zone lacks.
  void onResumed(const proto::Welcome& w, std::int64_t now_ns);
  /// A new session's stream: its datagram seqs, ticks and spawns start afresh, and the
  /// gateway will spawn everything in view again.
  void startNewStream();
  /// [gateway, fallback_gateways...][index].
  const Endpoint& knownGateway(std::size_t index) const;
  bool isKnownGateway(const Endpoint& e) const;
  /// Handoff and Pong (FlatBuffers).
  void onMessage(const proto::Datagram& d, std::int64_t now_ns);
  /// A checked lean frame: Spawn, StateBatch or Despawn (wire/downlink_frame.h).
  void onFrame(const gateway::DownlinkFrame& f, std::int64_t now_ns);
  void onSpawn(const gateway::DownlinkFrame& f, std::int64_t now_ns);
  void onStates(const gateway::DownlinkFrame& f, std::int64_t now_ns);
  void onDespawn(const gateway::DownlinkFrame& f);
  /// Whether a numbered datagram is new (acknowledging it); false for a duplicate.
  bool fresh(std::uint32_t seq);
  /// Whether a spawn or despawn in datagram seq is newer than the last one applied to id.
  bool newerLifecycle(std::uint64_t id, std::uint32_t seq);
  /// Logs the sampled entities as shown at the current whole server tick, once per tick;
  /// returns when the next tick starts.
  std::int64_t logDisplay(std::int64_t now_ns);
  /// Logs an own-avatar state or a handoff (up to kMaxOwnEvents).
  void logOwn(std::int64_t now_ns, std::uint64_t tick, bool handoff);
  /// Unpacks a frame's states and follows its server tick; nullopt (counted as out of range) if
  /// the stream is bad.
  std::optional<std::vector<dr::WireEntity>> unpack(const gateway::DownlinkFrame& f,
                                                    std::int64_t now_ns);

  PlayerConfig config_;
  // Every interface, so a gateway on another host is reached through the route's source address.
  gateway::UdpSocket socket_;
  std::uint64_t nonce_;
  std::uint64_t token_ = 0, player_id_ = 0, avatar_id_ = 0;
  int zone_ = -1;
  std::uint32_t seq_ = 0;
  std::size_t gateway_index_ = 0;  // the gateway played through now: [gateway, fallbacks...]
  std::vector<std::uint8_t> resume_token_;  // the newest Welcome's (empty: none)
  bool resuming_ = false;
  std::int64_t last_heard_ns_ = 0, resume_started_ns_ = 0, resume_gateway_since_ns_ = 0;
  std::int64_t last_ping_ns_ = 0;
  gateway::InputHistory sent_inputs_;  // the newest inputs, resent after a resume
  std::vector<gateway::InputRecord> earlier_;  // the ones the next Input carries again
  TransactionStream transactions_;     // the reliable transaction channel
  std::int64_t start_ns_, first_hello_ns_ = -1, welcome_ns_ = -1;
  std::int64_t next_hello_ns_, next_input_ns_, next_ping_ns_;
  std::int64_t next_leaderboard_ns_ = INT64_MAX;
  std::int64_t input_period_ns_;
  Wander wander_;
  RemoteView view_;
  gateway::Impairment impairment_;
  std::optional<dr::StateCodec> codec_;
  double tick_rate_ = 30;
  double dilation_ = 1;  // the zones' clock rate, from the newest Pong
  /// Server ticks per wall second: the tick rate slowed by time dilation.
  double ticksPerSecond() const { return tick_rate_ * dilation_; }
  /// Takes a Pong's time dilation factor: the clock keeps its place and changes its rate.
  void setDilation(float factor, std::int64_t now_ns);
  double clock_tick_ = -1;  // the tick the clock was last set to, and when
  std::int64_t clock_ns_ = 0;
  double newest_tick_ = -1;                                  // the newest server tick heard of
  std::uint64_t handoffs_seen_ = 0, last_handoff_tick_ = 0;  // the newest handoff applied
  PlayerCounters counters_;
  gateway::AckWindow acks_;
  // Per entity, the seq of the last Spawn or Despawn applied: a resent or reordered older one
  // must not bring back a despawned entity or remove a respawned one.
  std::unordered_map<std::uint64_t, std::uint32_t> lifecycle_;
  struct Unknown {
    std::int64_t first_ns, last_ns;
  };
  std::unordered_map<std::uint64_t, Unknown> unknown_;  // updated but not spawned here
  std::vector<std::uint8_t> rx_buffer_;
  std::vector<OwnEvent> own_;
  std::vector<DisplaySample> displayed_;
  std::int64_t displayed_tick_ = -1;  // the last server tick logged
  double visible_sum_ = 0;            // view sizes at each input sent, for meanVisible()
  std::uint64_t visible_samples_ = 0;
};

}  // namespace zonesim::clients
