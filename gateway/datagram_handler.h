#pragma once
// Turns one received datagram into effects: replies to send, avatars to request, inputs to
// forward, sessions that ended. It does no I/O itself, so every path is testable with crafted
// bytes; the gateway carries the effects out on UDP and DDS. Anything malformed, forged or from
// the wrong address is dropped and counted by reason.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "auth/auth_key.h"
#include "auth/connect_token.h"
#include "auth/resume_token.h"
#include "common/rng.h"
#include "common/scene_geometry.h"
#include "gateway/session_table.h"
#include "gateway/token_gate.h"
#include "wire/wire_encode.h"
#include "wire/wire_verify.h"

namespace zonesim::gateway {

/// Ask the zones to create an avatar for a player at a position.
struct SpawnCommand {
  std::uint64_t player_id = 0;
  float x = 0, y = 0, z = 0;
  std::uint8_t kind = 0;  ///< the player's kind (common/player_kind.h), checked against the scene
  bool resumed = false;   ///< a player back with a resume token: its zone re-announces its avatar
  std::uint64_t session_id = 0;  ///< the session asking (Session::session_id)
};

/// One player input to forward to the avatar's owning zone.
struct InputCommand {
  std::uint64_t player_id = 0;
  std::uint64_t avatar_id = 0;
  int zone = 0;
  std::uint32_t seq = 0;
  float move_x = 0, move_z = 0;
};

/// One transaction to forward to the avatar's owning zone, which applies it once and answers
/// with its outcome (the client resends it until then).
struct TransactionCommand {
  std::uint64_t player_id = 0;
  int zone = 0;
  TransactionInfo tx;
};

/// A player asks for the leaderboard; its avatar's zone answers.
struct LeaderboardCommand {
  std::uint64_t player_id = 0;
  int zone = 0;
  std::uint8_t count = 0;
};

/// A datagram to send back to the address a request came from.
struct Reply {
  Endpoint to;
  std::uint64_t token = 0;  ///< the session it belongs to (for per-player counts)
  Bytes bytes;
};

/// Effects of handling datagrams, carried out by the caller.
struct Outbox {
  std::vector<Reply> replies;
  std::vector<SpawnCommand> spawns;
  std::vector<InputCommand> inputs;
  std::vector<TransactionCommand> transactions;
  std::vector<LeaderboardCommand> leaderboards;
  std::vector<Session> closed;  ///< sessions ended by Bye (already erased): release interest
  /// Sessions a resumed Hello of the same player replaced (already erased): release interest,
  /// but keep the avatar, which the new session goes on with.
  std::vector<Session> replaced;
  void clear();
};

/// What the handler needs to know of the world.
struct HandlerConfig {
  SceneBox world;
  float tick_rate = 30;
  std::uint64_t spawn_seed = 1;  ///< seeds spawn positions (reproducible runs)
  dr::CodecParams codec;         ///< how states are packed (sent in the Welcome)
  float sim_dt = 1.0f / 30;      ///< simulated seconds per zone tick
  double rate_per_s = 100;       ///< datagrams per second a session may send (sustained)
  double rate_burst = 50;        ///< and in a burst
  /// The cluster's key: a Hello then needs the lobby's connect token for this gateway
  /// (gateway/token_gate.h). nullopt: any Hello opens a session, as without a lobby.
  std::optional<auth::AuthKey> auth_key{};
  std::uint16_t gateway_id = 0;  ///< the gateway tokens must be signed for
  /// The key the cluster's gateways share for resume tokens (auth/resume_token.h): each
  /// Welcome carries one, and a Hello with one comes back as its player. nullopt: no resume.
  std::optional<auth::AuthKey> resume_key{};
  double resume_valid_s = 86400;  ///< how long a Welcome's resume token is good for
  /// The player kinds the scene lists: bit i for kind id i (common/player_kind.h). A Hello of
  /// any other kind is refused. Default: walkers only, a scene without `clients.kinds`.
  std::uint32_t kinds = 1;
  /// The wall clock (Unix ms) tokens expire by; tests set their own.
  std::function<std::uint64_t()> unix_now_ms = auth::unixNowMs;
};

class DatagramHandler {
 public:
  DatagramHandler(SessionTable& sessions, const HandlerConfig& config);

  /// Handles one datagram of size bytes.size() from `from`.
  void handle(std::span<const std::uint8_t> bytes, const Endpoint& from, std::int64_t now_ns,
              Outbox& out);
  /// The Welcome for a session whose avatar is known.
  Bytes welcomeFor(const Session& s) const;

  const DropCounters& drops() const { return drops_; }
  /// The zones' time dilation factor, told to every client in its Pongs.
  void setDilation(double factor) { dilation_ = float(factor); }
  /// Counts an oversize datagram the socket truncated before it reached handle().
  void countTooLarge() { drops_.add(DropReason::TooLarge); }
  std::uint64_t accepted() const { return accepted_; }
  /// Inputs whose own datagram was lost, forwarded from a later one that carried them again.
  std::uint64_t inputsRecovered() const { return inputs_recovered_; }
  /// The connect-token check, when the gateway has a key (nullptr otherwise).
  const TokenGate* tokenGate() const { return gate_ ? &*gate_ : nullptr; }

 private:
  void onHello(const proto::Datagram& d, const Endpoint& from, std::size_t size,
               std::int64_t now_ns, Outbox& out);
  /// Checks a Hello's resume token: the player it brings back, or nullopt (counted).
  std::optional<auth::ResumeToken> checkResume(std::span<const std::uint8_t> token,
                                               const Endpoint& from);
  void onInput(const proto::Input& in, Session& s, Outbox& out);
  /// Passes one input on to the avatar's zone and keeps it for a resend after a restart.
  void forwardInput(const InputRecord& in, Session& s, Outbox& out);
  void onTransaction(const proto::Transaction& t, Session& s, Outbox& out);
  /// Takes one token from the session's bucket; false (drop) when it is empty.
  bool withinRate(Session& s, std::int64_t now_ns) const;
  /// The session the datagram's token names, if it comes from that session's address.
  Session* authenticate(const proto::Datagram& d, const Endpoint& from, SlotHandle& handle);

  SessionTable& sessions_;
  HandlerConfig config_;
  Pcg32 spawn_rng_;
  std::optional<TokenGate> gate_;
  DropCounters drops_;
  std::uint64_t accepted_ = 0;
  std::uint64_t inputs_recovered_ = 0;
  float dilation_ = 1.0f;  // the zones' clock rate, for Pongs
};

}  // namespace zonesim::gateway
