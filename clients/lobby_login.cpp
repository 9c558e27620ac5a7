#include "clients/lobby_login.h"

#include <algorithm>
#include <cerrno>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

#include "common/due_queue.h"
#include "common/splitmix.h"
#include "common/timer.h"
#include "wire/epoll_set.h"
#include "wire/lobby_wire.h"

namespace zonesim::clients {

namespace {

/// One player's login in progress.
struct Pending {
  std::uint64_t nonce = 0;
  std::int64_t next_send_ns = 0;
  std::optional<LoginTicket> ticket;
};

/// Reads every reply pending on one socket into its login.
void receive(gateway::UdpSocket& socket, Pending& p, const LobbyLoginSettings& s,
             std::int64_t now_ns, std::vector<std::uint8_t>& buf, LoginStats& stats,
             std::string& last_refusal, bool& final_refusal) {
  for (;;) {
    auto got = socket.receive(buf);
    if (!got) return;
    if (got->from != s.lobby) {
      stats.drops.add(gateway::DropReason::WrongAddress);
      continue;
    }
    if (got->truncated || got->size > gateway::kMaxDatagramBytes) {
      stats.drops.add(gateway::DropReason::TooLarge);
      continue;
    }
    gateway::LobbyVerified v = gateway::verifyLobbyDatagram(std::span(buf.data(), got->size),
                                                            gateway::LobbyDirection::ToPlayer);
    if (!v.ok()) {
      stats.drops.add(v.reason);
      continue;
    }
    if (const auto* g = v.datagram->msg_as_LoginGranted()) {
      if (g->request_nonce() != p.nonce || p.ticket) continue;  // an old or repeated answer
      LoginTicket t;
      t.gateway = {g->gateway_address(), g->gateway_port()};
      t.gateway_id = g->gateway_id();
      t.player_id = g->player_id();
      t.connect_token.assign(g->connect_token()->begin(), g->connect_token()->end());
      p.ticket = std::move(t);
    } else if (const auto* r = v.datagram->msg_as_LoginRefused()) {
      if (r->request_nonce() != p.nonce) continue;
      ++stats.refusals;
      last_refusal = r->reason() != nullptr ? r->reason()->str() : "no reason given";
      if (!r->retry()) final_refusal = true;
      // Asked again after the retry period, not at once: the lobby is waiting on gateways.
      p.next_send_ns = std::max(p.next_send_ns, now_ns + std::int64_t(s.retry_s * 1e9));
    }
  }
}

}  // namespace

std::vector<LoginTicket> loginAll(std::span<gateway::UdpSocket> sockets,
                                  const LobbyLoginSettings& s, const std::atomic<bool>& stop,
                                  LoginStats* stats_out) {
  LoginStats local_stats;
  LoginStats& stats = stats_out != nullptr ? *stats_out : local_stats;
  std::int64_t start = nowNs();
  std::int64_t deadline = start + std::int64_t(s.timeout_s * 1e9);
  std::int64_t retry_ns = std::max<std::int64_t>(1, std::int64_t(s.retry_s * 1e9));
  std::vector<Pending> pending(sockets.size());
  for (std::size_t i = 0; i < sockets.size(); ++i) {
    // Nonces only match replies to requests; mixing in the port keeps two runs apart.
    pending[i].nonce = splitmix64(s.seed ^ (std::uint64_t{i} << 32) ^ 0x10bb1) ^
                       std::uint64_t(sockets[i].localPort());
    if (pending[i].nonce == 0) pending[i].nonce = 1;
    pending[i].next_send_ns = start;
  }
  // Replies come one per socket, in any order: an epoll wait costs the sockets that answered,
  // and the queue of next sends the requests that are due, where a scan of all was O(players)
  // per reply.
  gateway::EpollSet ready;
  DueQueue sends(sockets.size());
  for (std::size_t i = 0; i < sockets.size(); ++i) {
    ready.add(sockets[i].fd(), i);
    sends.arm(i, pending[i].next_send_ns);
  }
  std::vector<std::size_t> due;
  std::vector<std::uint8_t> buf(gateway::kMaxDatagramBytes + 1);
  std::string last_refusal;
  bool final_refusal = false;
  std::size_t granted = 0;
  while (granted < sockets.size() && !stop.load(std::memory_order_relaxed)) {
    std::int64_t now = nowNs();
    if (now >= deadline || final_refusal) {
      std::string why = last_refusal.empty() ? "no answer" : "last refusal: " + last_refusal;
      throw std::runtime_error(
          "lobby " + s.lobby.str() + ": " + std::to_string(sockets.size() - granted) + " of " +
          std::to_string(sockets.size()) + " players got no gateway " +
          (final_refusal ? "" : "within " + std::to_string(s.timeout_s) + " s ") + "(" + why + ")");
    }
    due.clear();
    sends.popDue(now, due);
    for (std::size_t i : due) {
      sockets[i].sendTo(s.lobby, gateway::encodeLoginRequest(pending[i].nonce, "player"));
      ++stats.requests;
      pending[i].next_send_ns = now + retry_ns;
      sends.arm(i, pending[i].next_send_ns);
    }
    int n = ready.wait(std::min(deadline, sends.nextDue()));
    now = nowNs();
    for (int k = 0; k < n; ++k) {
      std::size_t i = std::size_t(ready.key(k));
      Pending& p = pending[i];
      receive(sockets[i], p, s, now, buf, stats, last_refusal, final_refusal);
      if (!p.ticket) {
        sends.arm(i, p.next_send_ns);  // a refusal puts the next request off
        continue;
      }
      ++granted;
      sends.disarm(i);
      ready.remove(sockets[i].fd());  // done: its socket is the player's from now on
    }
  }
  std::vector<LoginTicket> out;
  if (granted < sockets.size()) return out;  // stopped
  out.reserve(granted);
  for (Pending& p : pending)
    if (p.ticket) out.push_back(std::move(*p.ticket));
  return out;
}

}  // namespace zonesim::clients
