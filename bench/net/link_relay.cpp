// link_relay: puts players that have no link model of their own (the Python players that time
// client-server latency in bench/net/topology_bench.py) behind the one client_stub and
// topology_node use (wire/impairment.h, docs/networking.md "Link impairment"), instead of a
// second model written in Python. Each of --pairs pairs of UDP sockets relays one player to
// one server: what the player sends goes through its uplink model and out of the pair's own
// server-facing socket (so the server sees one address per player), what the server sends
// back goes through the player's downlink model. Both directions take the --link profile, as
// client_stub --link gives its players; the relay's own hop adds loopback's tens of µs.
//
//   link_relay --to 127.0.0.1:PORT --link 4g --pairs 4 --port-file F [--seed S] [--duration S]
//
// F gets the player-facing ports, one a line, once all are bound. A pair relays for the first
// address that writes to it and drops anything from elsewhere (counted in the summary).
#include <poll.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/cli.h"
#include "common/stop_signal.h"
#include "common/text_file.h"
#include "common/timer.h"
#include "wire/drop_reason.h"
#include "wire/impairment.h"
#include "wire/link_profile.h"
#include "wire/udp_socket.h"

namespace {

using zonesim::gateway::Endpoint;
using zonesim::gateway::Impairment;
using zonesim::gateway::ImpairmentSettings;
using zonesim::gateway::LinkCounters;
using zonesim::gateway::LinkProfile;
using zonesim::gateway::UdpSocket;

// One player's link: its two sockets and a model each way.
struct Pair {
  Pair(const LinkProfile& profile, std::uint64_t seed, std::uint64_t index)
      : player_side(Endpoint::loopback(0)),
        server_side(Endpoint::loopback(0)),
        up(ImpairmentSettings{profile, {}, seed}, 2 * index),
        down(ImpairmentSettings{profile, {}, seed}, 2 * index + 1) {}
  UdpSocket player_side, server_side;
  Impairment up, down;
  std::optional<Endpoint> player;
  std::uint64_t foreign = 0;  // datagrams from neither the player nor the server
};

std::string countersJson(const LinkCounters& c) {
  char text[200];
  std::snprintf(text, sizeof text,
                "{\"offered\":%llu,\"lost\":%llu,\"tail_dropped\":%llu,\"delivered\":%llu}",
                (unsigned long long)c.offered, (unsigned long long)c.lost,
                (unsigned long long)c.tail_dropped, (unsigned long long)c.delivered);
  return text;
}

void relay(std::vector<std::unique_ptr<Pair>>& pairs, const Endpoint& server, double duration_s) {
  std::int64_t end = duration_s > 0 ? zonesim::nowNs() + std::int64_t(duration_s * 1e9) : 0;
  alignas(8) std::uint8_t buf[zonesim::gateway::kMaxDatagramBytes + 1];
  std::vector<pollfd> fds;
  for (const auto& p : pairs) {
    fds.push_back({p->player_side.fd(), POLLIN, 0});
    fds.push_back({p->server_side.fd(), POLLIN, 0});
  }
  while (!zonesim::stopRequested().load()) {
    std::int64_t now = zonesim::nowNs();
    if (end && now >= end) return;
    // Held datagrams are due at their own times; wake at least every 100 ms for the stop flag.
    std::int64_t wake = now + 100'000'000;
    if (end) wake = std::min(wake, end);
    for (const auto& p : pairs) wake = std::min({wake, p->up.nextDueNs(), p->down.nextDueNs()});
    zonesim::gateway::pollUntil(fds, wake);
    now = zonesim::nowNs();
    for (auto& p : pairs) {
      p->up.flush(p->server_side, now);
      p->down.flush(p->player_side, now);
      while (auto r = p->player_side.receive(buf)) {
        if (!p->player) p->player = r->from;
        if (r->truncated || r->from != *p->player) {
          ++p->foreign;
          continue;
        }
        p->up.send(p->server_side, server, {buf, r->size}, now);
      }
      while (auto r = p->server_side.receive(buf)) {
        if (r->truncated || r->from != server || !p->player) {
          ++p->foreign;
          continue;
        }
        p->down.send(p->player_side, *p->player, {buf, r->size}, now);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"zonesim link_relay: players behind the project's link model, relayed to a server"};
  zonesim::CommonOptions common;
  zonesim::addCommonOptions(app, common);
  std::string to, link, port_file;
  std::size_t count = 1;
  std::uint64_t seed = 1;
  double duration = 0;
  app.add_option("--to", to, "the server, HOST:PORT")->required();
  app.add_option("--link", link,
                 "each player's uplink and downlink: a preset (lan, wifi, 4g, congested, "
                 "satellite) or a profile file, as client_stub --link")
      ->required();
  app.add_option("--pairs", count, "players to relay, one port each")->check(CLI::Range(1, 256));
  app.add_option("--port-file", port_file, "write the players' ports here, one a line")->required();
  app.add_option("--seed", seed, "seed of the link models");
  app.add_option("--duration", duration, "exit after this many seconds (0 = until signalled)")
      ->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);
  zonesim::installStopSignals();
  try {
    zonesim::applyCommonOptions(common, "link_relay");
    Endpoint server = zonesim::gateway::resolveEndpoint(to);
    LinkProfile profile;
    try {
      profile = zonesim::gateway::loadLinkProfile(link);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--link: ") + e.what());
    }
    std::vector<std::unique_ptr<Pair>> pairs;
    std::string ports;
    for (std::size_t i = 0; i < count; ++i) {
      pairs.push_back(std::make_unique<Pair>(profile, seed, i));
      ports += std::to_string(pairs.back()->player_side.localPort()) + "\n";
    }
    zonesim::writeTextFileAtomically(port_file, ports);
    std::printf("link_relay: %zu players behind %s to %s\n", count, profile.name.c_str(),
                server.str().c_str());
    std::fflush(stdout);
    relay(pairs, server, duration);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const Pair& p = *pairs[i];
      std::printf("link_relay summary {\"pair\":%zu,\"up\":%s,\"down\":%s,\"foreign\":%llu}\n", i,
                  countersJson(p.up.counters().out).c_str(),
                  countersJson(p.down.counters().out).c_str(), (unsigned long long)p.foreign);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "link_relay: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
