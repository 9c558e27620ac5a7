// client_stub's login against lobbies that do not grant: no answer, or refusals, end in one
// error naming the lobby, how many players got no gateway and the lobby's last reason.
#include "clients/lobby_login.h"

#include <gtest/gtest.h>
#include <poll.h>

#include <atomic>
#include <thread>

#include "wire/lobby_wire.h"

namespace zonesim::clients {
namespace {

std::string loginError(std::vector<gateway::UdpSocket>& players, const gateway::Endpoint& lobby) {
  LobbyLoginSettings s;
  s.lobby = lobby;
  s.retry_s = 0.05;
  s.timeout_s = 0.3;
  std::atomic<bool> stop{false};
  try {
    loginAll(players, s, stop);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(LobbyLogin, SilentLobbyIsAnErrorNamingIt) {
  gateway::UdpSocket lobby(gateway::Endpoint::loopback(0));
  std::vector<gateway::UdpSocket> players;
  for (int i = 0; i < 2; ++i) players.emplace_back(gateway::Endpoint::loopback(0));
  std::string e = loginError(players, lobby.local());
  EXPECT_NE(e.find("lobby " + lobby.local().str()), std::string::npos) << e;
  EXPECT_NE(e.find("2 of 2 players got no gateway"), std::string::npos) << e;
  EXPECT_NE(e.find("no answer"), std::string::npos) << e;
}

TEST(LobbyLogin, RefusalsAreRetriedAndTheLastReasonReported) {
  gateway::UdpSocket lobby(gateway::Endpoint::loopback(0));
  std::atomic<bool> done{false};
  std::atomic<int> requests{0};
  std::thread refuser([&] {
    std::vector<std::uint8_t> buf(gateway::kMaxDatagramBytes + 1);
    while (!done) {
      pollfd p{lobby.fd(), POLLIN, 0};
      if (::poll(&p, 1, 10) <= 0) continue;
      while (auto got = lobby.receive(buf)) {
        auto v = gateway::verifyLobbyDatagram(std::span(buf.data(), got->size),
                                              gateway::LobbyDirection::ToLobby);
        if (!v.ok()) continue;
        ++requests;
        lobby.sendTo(got->from,
                     gateway::encodeLoginRefused(v.datagram->msg_as_LoginRequest()->request_nonce(),
                                                 true, "every gateway is full"));
      }
    }
  });
  std::vector<gateway::UdpSocket> players;
  players.emplace_back(gateway::Endpoint::loopback(0));
  std::string e = loginError(players, lobby.local());
  done = true;
  refuser.join();
  EXPECT_NE(e.find("1 of 1 players got no gateway"), std::string::npos) << e;
  EXPECT_NE(e.find("last refusal: every gateway is full"), std::string::npos) << e;
  EXPECT_GE(requests.load(), 2) << "a refusal worth retrying is retried";
}

}  // namespace
}  // namespace zonesim::clients
