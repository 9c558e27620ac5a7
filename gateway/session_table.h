#pragma once
// The gateway's sessions, one per connected player, in generation-checked slots so that a handle
// kept across a session's end never resolves to the player who got the slot next. Lookups by
// token, by player id and by (address, hello nonce) all go through handles.

#include <cstdint>
#include <optional>
#include <random>
#include <unordered_map>

#include "common/generational_pool.h"
#include "common/player_kind.h"
#include "gateway/client_view.h"
#include "gateway/downlink_budget.h"
#include "wire/input_history.h"
#include "wire/ack_window.h"
#include "wire/udp_socket.h"
#include "wire/wire_encode.h"

namespace zonesim::gateway {

/// Traffic figures of one session.
struct SessionTraffic {
  std::uint64_t datagrams_in = 0, bytes_in = 0;
  std::uint64_t datagrams_out = 0, bytes_out = 0;
  std::uint64_t updates_sent = 0, spawns_sent = 0, despawns_sent = 0;
  std::uint64_t inputs_forwarded = 0, handoffs = 0;
  std::uint64_t resent = 0;           ///< spawns, states and despawns sent again for want of an ack
  std::uint64_t handoffs_resent = 0;  ///< Handoff notices sent again for want of an ack
  std::uint64_t deferred = 0;         ///< spawns, updates and despawns held back a tick for want of budget
  std::uint64_t held = 0;             ///< updates not sent: the error shown stayed within the angle
};

/// The newest Handoff notice of a session, until the client acknowledges it.
struct PendingHandoff {
  HandoffInfo info;  ///< info.seq: the datagram that carried it last
  std::int64_t sent_ns = 0;
};

/// One player connected through this gateway.
struct Session {
  std::uint64_t token = 0;
  std::uint64_t player_id = 0;
  /// Unique in the cluster, as issued player ids are; zones match a despawn request to the
  /// session that asked for the avatar last (a resumed player's old session must not remove it).
  std::uint64_t session_id = 0;
  std::uint64_t client_nonce = 0;
  PlayerKindId kind = PlayerKindId::Walker;  ///< from the Hello: the nimbus and speed it gets
  Endpoint address;
  std::uint64_t avatar_id = 0;       ///< 0 until the owning zone announced the avatar
  int zone = -1;                     ///< owning zone rank, -1 until announced
  std::uint64_t owner_tick = 0;      ///< zone tick of the ownership event applied last
  std::uint32_t owner_epoch = 0;     ///< cluster epoch of that event
  bool respawning = false;           ///< the restored world lacks the avatar: a new one is asked
  bool welcomed = false;             ///< Welcome sent: inputs are accepted from now on
  bool resumed = false;              ///< opened by a resume token (auth/resume_token.h)
  std::uint32_t last_input_seq = 0;  ///< last seq forwarded to the zone
  InputHistory inputs;               ///< the newest forwarded, for resending after a restart
  std::uint32_t resend_from = 0;     ///< after a restart: resend inputs from this seq
  int resends_left = 0;              ///< bursts still to send (0: none due)
  std::int64_t next_resend_ns = 0;
  double spawn_x = 0, spawn_z = 0;   ///< where the avatar was requested (interest until it shows)
  std::int64_t created_ns = 0, last_heard_ns = 0;
  ClientView view;                        ///< what the client has been sent
  ResendTracker resend;                   ///< what of it the client has not acknowledged yet
  std::optional<PendingHandoff> handoff;  ///< sent, not yet acknowledged
  std::uint64_t told_tick = 0;  ///< the newest server tick a datagram to the client carried
  double rate_tokens = -1;      ///< per-client rate limit bucket; < 0: not started (full)
  std::int64_t rate_ns = 0;     ///< when the bucket was last refilled
  DownlinkBudget budget;        ///< used when the gateway has a downlink budget
  std::uint64_t bytes_out_at_second = 0;  ///< traffic.bytes_out when the metrics second began
  SessionTraffic traffic;
};

/// All sessions of one gateway.
class SessionTable {
 public:
  /// Player ids issued here are incarnation (15 bits) | gateway_id (16 bits) | counter (32
  /// bits): two gateways with different ids, or one gateway before and after a restart (a new
  /// random incarnation), never issue the same id.
  SessionTable(std::uint32_t gateway_id, std::size_t max_sessions, std::uint16_t incarnation = 0);

  /// A new pending session for a Hello; nullopt when max_sessions are open. player_id: the id
  /// a connect token grants (the lobby's, unique in the cluster); nullopt: one issued here.
  std::optional<SlotHandle> create(const Endpoint& address, std::uint64_t client_nonce,
                                   std::int64_t now_ns,
                                   std::optional<std::uint64_t> player_id = std::nullopt);
  /// The session a (repeated) Hello from this address with this nonce created.
  std::optional<SlotHandle> findByHello(const Endpoint& address, std::uint64_t client_nonce) const;
  std::optional<SlotHandle> findByToken(std::uint64_t token) const;
  std::optional<SlotHandle> findByPlayer(std::uint64_t player_id) const;
  /// The session, or nullptr if the handle is stale.
  Session* get(SlotHandle h) { return pool_.get(h); }
  const Session* get(SlotHandle h) const { return pool_.get(h); }
  /// Ends a session; false if the handle was already stale.
  bool erase(SlotHandle h);
  std::size_t size() const { return pool_.size(); }
  /// Visits sessions in slot order.
  template <typename F>
  void forEach(F&& f) {
    pool_.forEach(std::forward<F>(f));
  }

 private:
  struct HelloKey {
    Endpoint address;
    std::uint64_t nonce;
    friend bool operator==(const HelloKey&, const HelloKey&) = default;
  };
  struct HelloKeyHash {
    std::size_t operator()(const HelloKey& k) const {
      return EndpointHash()(k.address) ^
             std::hash<std::uint64_t>()(k.nonce * 0x9e3779b97f4a7c15ULL);
    }
  };
  std::uint64_t freshToken();
  /// incarnation | gateway id | serial: an id no other gateway, nor this one before a restart,
  /// issues.
  std::uint64_t issuedId(std::uint32_t serial) const;

  std::uint32_t gateway_id_;
  std::uint16_t incarnation_;
  std::size_t max_sessions_;
  std::uint32_t player_counter_ = 0, session_counter_ = 0;
  // Tokens must not be guessable: seeded from the OS entropy source, not from the scene seed.
  std::mt19937_64 token_rng_;
  GenerationalPool<Session> pool_;
  std::unordered_map<std::uint64_t, SlotHandle> by_token_;
  std::unordered_map<std::uint64_t, SlotHandle> by_player_;
  std::unordered_map<HelloKey, SlotHandle, HelloKeyHash> by_hello_;
};

}  // namespace zonesim::gateway
