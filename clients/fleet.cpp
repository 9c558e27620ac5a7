#include "clients/fleet.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <thread>

#include "clients/fd_limit.h"
#include "clients/fleet_summary.h"
#include "clients/kind_mix.h"
#include "common/due_queue.h"
#include "common/timer.h"
#include "wire/datagram_batch.h"
#include "wire/epoll_set.h"

namespace zonesim::clients {

namespace {
constexpr std::int64_t kSecondNs = 1'000'000'000;
}

ClientFleet::ClientFleet(const FleetConfig& config, const std::atomic<bool>& stop)
    : config_(config), start_ns_(nowNs()) {
  // Before the first socket: past the hard limit, nothing is created.
  raiseFdLimit(fleetDescriptors(std::size_t(std::max(config.players, 0))));
  std::vector<gateway::UdpSocket> sockets;
  int players = config.players;
  if (config.lobby) {
    sockets.reserve(std::size_t(players));
    for (int i = 0; i < players; ++i) sockets.emplace_back(gateway::Endpoint::any(0));
    tickets_ = loginAll(sockets, *config.lobby, stop, &login_stats_);
    players = int(tickets_.size());
  }
  players_.reserve(std::size_t(players));
  // By the configured count, as the link shares: a player's kind does not depend on how many
  // the lobby let in.
  std::vector<PlayerKind> kinds = assignKinds(config.kinds, std::size_t(config.players));
  for (int i = 0; i < players; ++i) {
    PlayerConfig player = config.player;
    if (!kinds.empty()) player.kind = kinds[std::size_t(i)];
    if (!config.links.empty()) {
      std::size_t share =
          gateway::linkShareOf(config.links, std::size_t(i), std::size_t(config.players));
      player.impairment.out = player.impairment.in = config.links[share].profile;
    }
    if (config.lobby) {
      // It plays from the socket it logged in from: the token names that address and port.
      player.gateway = tickets_[std::size_t(i)].gateway;
      player.connect_token = tickets_[std::size_t(i)].connect_token;
      players_.push_back(std::make_unique<SimPlayer>(player, std::uint32_t(i), start_ns_,
                                                     std::move(sockets[std::size_t(i)])));
    } else {
      players_.push_back(std::make_unique<SimPlayer>(player, std::uint32_t(i), start_ns_));
    }
  }
  if (!config.metrics_path.empty()) metrics_ = MetricsWriter(config.metrics_path);
}

int ClientFleet::welcomed() const {
  return int(
      std::count_if(players_.begin(), players_.end(), [](const auto& p) { return p->welcomed(); }));
}

void ClientFleet::run(const std::atomic<bool>& stop) {
  start_ns_ = nowNs();
  std::int64_t cpu_start_ns = threadCpuNs(), process_start_ns = processCpuNs();
  std::int64_t end_ns = start_ns_ + std::int64_t(config_.duration_s * 1e9);
  std::int64_t next_metrics = start_ns_ + kSecondNs;
  gateway::EpollSet ready;
  for (std::size_t i = 0; i < players_.size(); ++i) ready.add(players_[i]->fd(), i);
  gateway::ReceiveBatch batch(gateway::kMaxDatagramBytes);
  DueQueue due(players_.size());
  for (std::size_t i = 0; i < players_.size(); ++i) due.arm(i, start_ns_);
  std::vector<std::size_t> acting;
  std::uint64_t wakeups = 0;
  while (!stop.load(std::memory_order_relaxed)) {
    std::int64_t now = nowNs();
    if (now >= end_ns) break;
    acting.clear();
    due.popDue(now, acting);
    // In player order, as the scan of every player was; act() says when each is next due,
    // held datagrams either way included.
    std::sort(acting.begin(), acting.end());
    for (std::size_t i : acting) due.arm(i, players_[i]->act(now));
    if (now >= next_metrics) {
      writeMetrics(now);
      next_metrics += kSecondNs;
    }
    int n = ready.wait(std::min({end_ns, next_metrics, due.nextDue()}));
    ++wakeups;
    now = nowNs();
    for (int k = 0; k < n; ++k) {
      std::size_t i = std::size_t(ready.key(k));
      players_[i]->receive(now, batch);
      // What arrived can bring its next action forward (a Welcome starts the inputs, a held
      // datagram joins the downlink, a new server tick moves the display log): it acts at the
      // next wake-up, as every player did when all of them were asked.
      due.arm(i, now);
    }
  }
  elapsed_s_ = double(nowNs() - start_ns_) * 1e-9;
  cost_ = {elapsed_s_, double(threadCpuNs() - cpu_start_ns) * 1e-9,
           double(processCpuNs() - process_start_ns) * 1e-9, wakeups};
  for (auto& p : players_) p->bye();
  flushByes();
  writeMetrics(nowNs());
  metrics_.flush();
  writeOwnStream();
  writeDisplayed();
}

void ClientFleet::flushByes() {
  // A Bye held on an impaired uplink goes out when due, as on the real link; left behind, it
  // would leave the gateway resending to a closed player until the session timed out.
  DueQueue held(players_.size());
  std::int64_t now = nowNs();
  for (std::size_t i = 0; i < players_.size(); ++i)
    if (std::int64_t next = players_[i]->flushUplink(now); next != INT64_MAX) held.arm(i, next);
  std::vector<std::size_t> due;
  while (!held.empty()) {
    std::this_thread::sleep_for(
        std::chrono::nanoseconds(std::max<std::int64_t>(0, held.nextDue() - nowNs())));
    now = nowNs();
    due.clear();
    held.popDue(now, due);
    for (std::size_t i : due)
      if (std::int64_t next = players_[i]->flushUplink(now); next != INT64_MAX) held.arm(i, next);
  }
}

void ClientFleet::writeDisplayed() const {
  if (config_.display_path.empty()) return;
  std::FILE* f = std::fopen(config_.display_path.c_str(), "w");
  if (f == nullptr) throw std::runtime_error("cannot write " + config_.display_path);
  std::fprintf(f, "player,tick,id,order,x,y,z,distance\n");
  for (std::size_t i = 0; i < players_.size(); ++i)
    for (const DisplaySample& d : players_[i]->displayed())
      std::fprintf(f, "%zu,%llu,%llu,%d,%.4f,%.4f,%.4f,%.2f\n", i,
                   static_cast<unsigned long long>(d.tick), static_cast<unsigned long long>(d.id),
                   int(d.order), d.x, d.y, d.z, d.distance);
  std::fclose(f);
}

void ClientFleet::writeOwnStream() const {
  if (config_.own_stream_path.empty()) return;
  std::FILE* f = std::fopen(config_.own_stream_path.c_str(), "w");
  if (f == nullptr) throw std::runtime_error("cannot write " + config_.own_stream_path);
  // "U": a new state of the player's own avatar arrived (tick = its sample tick); "H": a
  // Handoff notice (tick = the crossing tick). server_tick is the player's clock estimate.
  std::fprintf(f, "player,event,t_ms,tick,server_tick\n");
  for (std::size_t i = 0; i < players_.size(); ++i)
    for (const OwnEvent& e : players_[i]->ownStream())
      std::fprintf(f, "%zu,%c,%.3f,%llu,%.3f\n", i, e.handoff ? 'H' : 'U',
                   double(e.t_ns - start_ns_) * 1e-6, static_cast<unsigned long long>(e.tick),
                   e.server_tick);
  std::fclose(f);
}

void ClientFleet::writeMetrics(std::int64_t now_ns) {
  if (!metrics_.enabled()) return;
  PlayerCounters now = totalCounters(players_, false);
  double t = double(now_ns - start_ns_) * 1e-9;
  metrics_.write(fleetMetricsLine(players_, t, now, last_totals_, 1.0));
  last_totals_ = std::move(now);
}

std::string ClientFleet::summaryJson() const {
  double s = elapsed_s_ > 0 ? elapsed_s_ : double(nowNs() - start_ns_) * 1e-9;
  return fleetSummaryJson(players_, s, cost(), double(start_ns_) * 1e-9);
}

}  // namespace zonesim::clients
