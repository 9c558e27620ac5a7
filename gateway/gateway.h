#pragma once
// The gateway process: a UDP server for simulated players and a DDS link to the zones, driven
// by one loop that sleeps in poll() on the socket until the next gateway tick. Per datagram: the
// handler's checks and effects. Per tick: ownership events (Welcome, Handoff), cell samples into
// the world cache, interest (cell readers), and each player's Spawn / Despawn / StateBatch.

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "common/flat_id_map.h"
#include "common/interest_grid.h"
#include "common/metrics.h"
#include "common/scene.h"
#include "gateway/datagram_handler.h"
#include "gateway/epoch_timeline.h"
#include "gateway/gateway_metrics.h"
#include "gateway/gateway_recorder.h"
#include "gateway/interest_manager.h"
#include "gateway/load_report.h"
#include "gateway/session_table.h"
#include "gateway/world_cache.h"
#include "gateway/world_snapshot.h"
#include "gateway/zone_clock.h"
#include "gateway/zone_link.h"
#include "wire/datagram_batch.h"
#include "wire/impairment.h"
#include "wire/udp_socket.h"

namespace zonesim::gateway {

/// Everything a gateway is configured with.
struct GatewayConfig {
  Scene scene;
  Endpoint bind = Endpoint::loopback(0);  ///< UDP address for players; port 0 = ephemeral
  std::uint32_t gateway_id = 1;           ///< 1..65535, bits 32-47 of the player ids issued here
  int dds_domain = 0;
  std::uint64_t spawn_seed = 1;   ///< seeds avatar spawn positions
  int expected_zones = 0;         ///< readers awaited before spawning; 0 = the scene's grid
  double session_timeout_s = 10;  ///< a session silent this long is closed
  double pending_timeout_s = 5;   ///< a session still without avatar after this is dropped
  std::size_t max_sessions = 4096;
  double lookahead_s = 1.0;       ///< interest margin ahead of motion: speed * lookahead
  double handoff_grace_s = 0;     ///< leave grace; 0 = two zone ticks, at least 50 ms
  std::string metrics_path;       ///< gateway.jsonl; empty = no metrics
  ImpairmentSettings impairment;  ///< loss / delay / reordering injected on the UDP side
  bool resend =
      true;  ///< resend unacknowledged spawns, states and despawns (false: for comparison)
  LossDetection loss_detection = LossDetection::Timeout;  ///< when a datagram counts as lost
  /// A client that was sent nothing for this many zone ticks gets an empty StateBatch with
  /// the current tick, so its clock (bounded to run a little past the newest tick it heard,
  /// clients/sim_player.h) keeps running while its view is quiet. 0: never.
  int clock_every_ticks = 6;
  /// Without a budget, a player's visibility (spawns, despawns) is scanned every this many
  /// ticks, staggered over the players; the ticks between send the updates of what it holds
  /// from each cell's list of changed entities, shared by everyone who sees the cell.
  /// 1: a full scan every tick. (Under a budget every tick scans: waiting spawns are ranked
  /// each tick.)
  int full_scan_every_ticks = 4;
  /// Downlink budget per client (kbps 0: none, every update goes out as the zones sent it).
  BudgetSettings budget;
  /// How an error about the budget names its two settings (an option, or a scene key).
  std::pair<std::string, std::string> budget_names{"budget_kbps", "budget_error_angle_deg"};
  /// The cluster's key (--auth-key-file): every Hello needs the lobby's connect token, and the
  /// gateway reports its load to the lobby once a second. nullopt: no lobby, as before.
  std::optional<auth::AuthKey> auth_key{};
  /// Where players reach this gateway, told to the lobby: address 0 means the bound address,
  /// port 0 the bound port (a gateway bound to 0.0.0.0 must name its address).
  Endpoint public_address{0, 0};
  /// The key the cluster's gateways share for resume tokens (--resume-key-file, by default the
  /// cluster's key): a player whose gateway died comes back to any of them as itself.
  std::optional<auth::AuthKey> resume_key{};
  /// gateway --record DIR: a recording (gateway/gateway_recorder.h); empty: none.
  std::string record_dir;
  /// A recorded frame every this many ticks: the players' views as they stand then, their
  /// bytes since the frame before. Each player's view is most of a frame (its visible set with
  /// positions, ~24 bytes an entity): every tick, 32 players of the demo would write ~10 MB/s.
  int record_every_ticks = 6;
};

class Gateway {
 public:
  /// Binds the socket and joins the DDS domain; throws on failure.
  explicit Gateway(GatewayConfig config);

  /// The bound UDP port.
  std::uint16_t port() const { return socket_.localPort(); }
  /// The bound UDP address and port.
  const Endpoint& local() const { return socket_.local(); }
  /// Runs until stop is true or duration_s (if > 0) has passed. Returns within one tick.
  void run(const std::atomic<bool>& stop, double duration_s = 0);
  /// The exit summary as JSON.
  std::string summaryJson();
  const GatewayCounters& counters() const { return counters_; }
  const DropCounters& drops() const { return handler_.drops(); }

 private:
  void receiveAll(std::int64_t now_ns);
  void carryOut(Outbox& out);
  /// Hands the queued datagrams to the kernel and counts what it took.
  void flushSends();
  void tick(std::int64_t now_ns);
  /// Tells this gateway's players the outcomes of their transactions the zones decided, and
  /// the leaderboards they asked for.
  void deliverOutcomes();
  /// The welcomed session of a player of this gateway, or null.
  Session* welcomedSessionOf(std::uint64_t player_id);
  void applyOwnership(const zonesim_dds_OwnershipEvent& e);
  /// After a restart (gateway_epochs.cpp): the first announcement of s's avatar in the new
  /// epoch; resends the inputs the restored zone lacks, and tells the client of a new avatar
  /// or zone.
  void adoptRestoredOwner(Session& s, const zonesim_dds_OwnershipEvent& e, std::uint64_t tick,
                          bool avatar_changed, bool zone_changed);
  /// Notices a newly entered epoch and, kResyncSeconds after, drops what the restored world
  /// did not bring back and asks avatars anew for players it lacks.
  void followEpochs(std::int64_t now_ns);
  /// Sends the due bursts of inputs to resend after a restart.
  void resendInputs(std::int64_t now_ns);
  void expireSessions(std::int64_t now_ns);
  void updateInterest(std::int64_t now_ns);
  void applyCellDelta(const CellDelta& delta);
  void sendViews(std::int64_t now_ns);
  /// Adds to diff what the client has not acknowledged within the timeout.
  void addResends(Session& s, ViewDiff& diff, std::int64_t now_ns);
  void sendView(Session& s, const ViewDiff& diff, std::int64_t now_ns);
  /// The newest states of ids, encoded once a tick (encoded_), into out; returns the newest
  /// sample tick among them, at least the clock's (a frame's batch tick).
  std::uint64_t encodedStates(const std::vector<std::uint64_t>& ids,
                              std::vector<dr::EncodedEntity>& out) const;
  /// Under a budget (gateway_budget.cpp): what of diff goes out this tick, holding the rest in
  /// the view: despawns first as far as the tokens reach, the avatar in every send, then
  /// near updates, near spawns and the rest by rank. `nimbus` is the player's full nimbus,
  /// before the budget narrowed the view; `now_ns` paces the view's narrowing.
  void budgetDiff(Session& s, ViewDiff& diff, const ViewPoint& at, double nimbus,
                  std::int64_t now_ns);
  /// Spawns and updates chosen to go out this tick (each list ascending).
  struct Fit {
    std::vector<std::uint64_t> spawns, updates;
  };
  /// `forced` and then the longest prefix of `ranked` (id, is a spawn) whose encoding adds at
  /// most `available` bytes to forced's; `forced` always goes.
  void fitting(const Session& s, const Fit& forced,
               const std::vector<std::pair<std::uint64_t, bool>>& ranked, double available,
               Fit& out) const;
  /// Bytes of the Despawn datagrams carrying ids.
  std::size_t despawnBytes(const Session& s, std::span<const std::uint64_t> ids) const;
  /// How many of ids (a prefix) fit in `available` bytes of Despawn datagrams; `bytes` gets
  /// that prefix's size.
  std::size_t fittingDespawns(const Session& s, const std::vector<std::uint64_t>& ids,
                              double available, std::size_t& bytes) const;
  /// Sends the session's pending Handoff notice under a new seq.
  void sendHandoff(Session& s, std::int64_t now_ns);
  /// Forgets the pending Handoff once acknowledged; sends it again after the timeout.
  void resendHandoff(Session& s, std::int64_t now_ns);
  void sendTo(Session& s, const Bytes& bytes);
  void sendTo(const Endpoint& to, const Bytes& bytes);
  /// With --record (gateway_record.cpp): a player's view as it holds it now, and the tick's
  /// frame with the subscribed cells.
  void recordView(const Session& s, const ViewPoint& at);
  void recordTick(double sim_now);
  void closeSession(SlotHandle h, bool expired);
  /// Bookkeeping for a player whose session ended: its figures, its interest, its avatar.
  void retirePlayer(const Session& s, CellDelta& delta);
  /// The same, keeping the avatar: a resumed session of the player goes on with it.
  void releasePlayer(const Session& s, CellDelta& delta);
  /// Ends a metrics second: each client's rate over it, and a gateway.jsonl line if enabled.
  void writeMetrics(std::int64_t now_ns);
  GatewayGauges gauges(std::int64_t now_ns);
  /// The process's CPU time since run() began, over the ticks run.
  double processCpuMsPerTick() const;
  /// The avatar's position as last heard (extrapolated), or the spawn point before that.
  void avatarPosition(const Session& s, double sim_now, double& x, double& z) const;
  /// The avatar's planar speed as last heard (0 before it is known).
  double avatarSpeed(const Session& s) const;
  /// The player's nimbus now (its kind's, grown with its speed).
  double nimbusOf(const Session& s) const;
  /// The scene's settings for the player's kind.
  const PlayerKind& kindOf(const Session& s) const { return kinds_[std::size_t(s.kind)]; }

  GatewayConfig config_;
  InterestGrid grid_;
  std::int64_t tick_ns_;
  std::int64_t start_ns_;
  UdpSocket socket_;
  SessionTable sessions_;
  DatagramHandler handler_;
  WorldCache cache_;
  WorldSnapshot snapshot_;              // the cache at this tick's sim time, for every view
  std::vector<VisibleEntity> visible_;  // one player's visible set, reused
  ViewDiff diff_;                       // one player's diff, reused
  ResendDue due_;                       // one player's resends, reused
  std::vector<std::uint64_t> scratch_ids_;
  std::vector<dr::EncodedEntity> encoded_scratch_;  // one send's states, reused
  FrameScratch frames_;                             // one send's frames, reused
  std::vector<std::size_t> chunk_counts_;           // entities per frame of one send
  // Budget sizing (fitting) encodes candidate sets into buffers of its own.
  mutable std::vector<dr::EncodedEntity> sizing_states_;
  mutable FrameScratch sizing_frames_;
  mutable Fit sizing_fit_;
  // budgetDiff's lists, kept: ranked entities (band, -priority, id, is a spawn), what goes.
  std::vector<std::tuple<int, double, std::uint64_t, bool>> budget_order_;
  std::vector<std::pair<std::uint64_t, bool>> budget_ranked_;
  Fit budget_forced_, budget_go_;
  ZoneClock clock_;
  EpochTimeline timeline_;                 // zone ticks of every epoch on one timeline
  std::int64_t resync_due_ns_ = 0;         // when the newest epoch's resync ends (0: none)
  std::vector<SlotHandle> resending_;      // sessions with input bursts still due
  InterestManager interest_;
  std::array<PlayerKind, kPlayerKindCount> kinds_;  // the scene's kinds by id
  ZoneLink link_;
  std::optional<LoadReport> load_report_;  // with a key: what the lobby knows of us
  MetricsWriter metrics_;
  GatewayCounters counters_;
  std::vector<PlayerRecord> finished_players_;
  Outbox outbox_;
  ReceiveBatch rx_batch_;  // recvmmsg buffers
  SendQueue send_queue_;   // datagrams of this tick or wake, sent with sendmmsg
  dr::StateCodec codec_;   // packs states for clients exactly as the zones quantised them
  std::unique_ptr<GatewayRecorder> recorder_;        // --record; null: nothing recorded
  std::vector<RecordedVisible> recorded_visible_;    // one player's, reused
  std::vector<std::pair<int, int>> recorded_cells_;  // the tick's cells and holders, reused
  // This tick's encoded states by id (cleared by sendViews): each entity is quantised once a
  // tick and shared by every player it goes to. Mutable: a memo that sizing fills too.
  mutable FlatIdMap<dr::EncodedState> encoded_;
  Impairment impairment_;
  std::int64_t next_metrics_ns_ = 0;
  // Under a budget: refill per tick, what a send waits for, what the bucket holds at most.
  double budget_bytes_per_tick_ = 0, budget_send_bytes_ = 0, budget_cap_bytes_ = 0;
  int budget_ticks_per_send_ = 1;
  std::int64_t last_views_ns_ = 0;      // when sendViews last ran (the budget refills by time)
  std::uint64_t views_ = 0;             // sendViews calls: full scans are staggered by it
  TickTimes tick_window_, tick_total_;  // this metrics second, and the whole run
  TickTimes tick_cpu_window_, tick_cpu_total_;  // the same in thread CPU time
  std::int64_t start_process_cpu_ns_ = 0;
  double worst_client_kbps_ = 0;      // the most any client was sent in one second
  std::vector<double> kbps_scratch_;  // per-second rates, reused
};

}  // namespace zonesim::gateway
