// A simulated player whose gateway falls silent, against UDP sockets that play the gateways
// with crafted datagrams, on a virtual clock: it probes with Pings first (a live gateway whose
// zones restart answers them and keeps its player), then says Hello with its Welcome's resume
// token, to the same gateway and then the next it knows, and on a resumed Welcome resends the
// inputs after the one the zone applied last; a resume nobody answers starts over as a new
// player.
#include <gtest/gtest.h>
#include <poll.h>

#include "clients/sim_player.h"
#include "common/timer.h"

namespace zonesim::clients {
namespace {

using gateway::Bytes;

constexpr std::int64_t kMs = 1'000'000;

// A datagram the player sent, decoded.
struct Sent {
  proto::Message type = proto::Message::NONE;
  std::uint64_t token = 0;
  std::uint64_t nonce = 0;                ///< Hello
  std::vector<std::uint8_t> resume;       ///< Hello's resume token
  std::uint32_t seq = 0;                  ///< Input
};

class SimPlayerResumeTest : public ::testing::Test {
 protected:
  void start(double give_up_s = 10) {
    PlayerConfig c;
    c.gateway = Endpoint::loopback(first_.localPort());
    c.fallback_gateways = {Endpoint::loopback(second_.localPort())};
    c.world = {{0, 0, 0}, {100, 10, 100}};
    c.resume_give_up_s = give_up_s;
    t_ = nowNs();
    player_ = std::make_unique<SimPlayer>(c, 0, t_);
  }

  // Everything the player sent to `gw` so far.
  std::vector<Sent> drain(gateway::UdpSocket& gw) {
    std::vector<Sent> out;
    pollfd p{gw.fd(), POLLIN, 0};
    while (::poll(&p, 1, 5) > 0) {
      auto got = gw.receive(buf_);
      if (!got) break;
      player_addr_ = got->from;
      auto v = gateway::verifyDatagram(std::span(buf_.data(), got->size),
                                       gateway::Direction::ToGateway);
      if (!v.ok()) continue;
      Sent s;
      s.type = v.datagram->msg_type();
      s.token = v.datagram->token();
      if (s.type == proto::Message::Hello) {
        const proto::Hello* h = v.datagram->msg_as_Hello();
        s.nonce = h->client_nonce();
        if (h->resume_token()) s.resume.assign(h->resume_token()->begin(), h->resume_token()->end());
      }
      if (s.type == proto::Message::Input) s.seq = v.datagram->msg_as_Input()->seq();
      out.push_back(std::move(s));
    }
    return out;
  }

  // Runs the player's clock on in 10 ms steps for ms milliseconds; what it sent to each gateway.
  void advance(std::int64_t ms) {
    for (std::int64_t end = t_ + ms * kMs; t_ < end;) {
      t_ += 10 * kMs;
      player_->act(t_);
    }
    for (Sent& s : drain(first_)) to_first_.push_back(std::move(s));
    for (Sent& s : drain(second_)) to_second_.push_back(std::move(s));
  }

  // The gateway's Welcome, answering a Hello with nonce, from gw.
  void welcome(gateway::UdpSocket& gw, std::uint64_t nonce, std::uint64_t token,
               std::uint32_t last_input_seq) {
    gateway::WelcomeInfo w;
    w.client_nonce = nonce;
    w.token = token;
    w.player_id = kPlayer;
    w.avatar_id = 77;
    w.zone = 1;
    w.world_max = proto::Vec3f(100, 10, 100);
    w.resume_token = kResumeToken;
    w.last_input_seq = last_input_seq;
    player_->handle(gateway::encodeWelcome(w), Endpoint::loopback(gw.localPort()), t_);
  }

  // The first Welcome, then 0.5 s of play (inputs 1..10 at 20 Hz) ended by a Pong: the last
  // datagram heard from the gateway.
  void play() {
    advance(10);
    ASSERT_FALSE(to_first_.empty());
    ASSERT_EQ(to_first_[0].type, proto::Message::Hello);
    welcome(first_, to_first_[0].nonce, kToken, 0);
    ASSERT_TRUE(player_->welcomed());
    to_first_.clear();
    advance(490);
    player_->handle(gateway::encodePong(kToken, 1, 2), Endpoint::loopback(first_.localPort()), t_);
  }

  static std::vector<Sent> ofType(const std::vector<Sent>& v, proto::Message t) {
    std::vector<Sent> out;
    for (const Sent& s : v)
      if (s.type == t) out.push_back(s);
    return out;
  }

  static constexpr std::uint64_t kPlayer = (1ull << 32) | 1, kToken = 0xabcdef;
  static inline const std::vector<std::uint8_t> kResumeToken = std::vector<std::uint8_t>(56, 7);
  gateway::UdpSocket first_, second_;
  std::unique_ptr<SimPlayer> player_;
  Endpoint player_addr_;
  std::int64_t t_ = 0;
  std::vector<Sent> to_first_, to_second_;
  std::vector<std::uint8_t> buf_ = std::vector<std::uint8_t>(2048);
};

TEST_F(SimPlayerResumeTest, SilenceProbesThenResumesAndResendsWhatTheZoneLacks) {
  start();
  play();
  std::uint32_t sent = player_->counters().inputs;
  ASSERT_GE(sent, 8u);
  // The gateway says nothing from now on. Half a second in, the player pings every 0.1 s.
  to_first_.clear();
  advance(490);
  EXPECT_LE(ofType(to_first_, proto::Message::Ping).size(), 1u) << "one a second until then";
  to_first_.clear();
  advance(400);
  EXPECT_GE(ofType(to_first_, proto::Message::Ping).size(), 3u) << "probing";
  EXPECT_TRUE(ofType(to_first_, proto::Message::Hello).empty()) << "not yet given up on it";
  // A second of silence: Hello with the resume token, to the same gateway, a new nonce.
  to_first_.clear();
  advance(300);
  std::vector<Sent> hellos = ofType(to_first_, proto::Message::Hello);
  ASSERT_FALSE(hellos.empty());
  EXPECT_EQ(hellos[0].resume, kResumeToken);
  EXPECT_EQ(hellos[0].token, 0u);
  EXPECT_FALSE(player_->welcomed());
  EXPECT_TRUE(to_second_.empty()) << "the same gateway first: it may be restarted";
  sent = std::uint32_t(player_->counters().inputs);

  // The restarted gateway takes it back; its zone had applied inputs 1..3.
  welcome(first_, hellos.back().nonce, kToken + 1, 3);
  ASSERT_TRUE(player_->welcomed());
  EXPECT_EQ(player_->playerId(), kPlayer);
  EXPECT_EQ(player_->avatarId(), 77u);
  const PlayerCounters& c = player_->counters();
  EXPECT_EQ(c.resumes, 1u);
  EXPECT_EQ(c.resume_new_avatar, 0u);
  EXPECT_EQ(c.resume_failed, 0u);
  EXPECT_EQ(c.inputs_resent, sent - 3);
  EXPECT_EQ(c.inputs_unresendable, 0u);
  ASSERT_EQ(c.resume_s.seen(), 1u);
  EXPECT_NEAR(c.resume_s.samples()[0], 1.2, 0.05) << "from the last datagram heard";
  to_first_.clear();
  advance(60);
  std::vector<Sent> inputs = ofType(to_first_, proto::Message::Input);
  ASSERT_GE(inputs.size(), sent - 3);
  for (std::uint32_t i = 0; i < inputs.size(); ++i) {
    EXPECT_EQ(inputs[i].seq, 4 + i) << "resent in order, then new ones";
    EXPECT_EQ(inputs[i].token, kToken + 1);
  }
}

// Zones restarting send no states; the gateway still answers Pings, and the player stays.
TEST_F(SimPlayerResumeTest, AnAnsweredProbeKeepsTheSession) {
  start();
  play();
  for (int i = 0; i < 5; ++i) {
    advance(400);
    player_->handle(gateway::encodePong(kToken, 1, 2), Endpoint::loopback(first_.localPort()), t_);
  }
  EXPECT_TRUE(player_->welcomed());
  EXPECT_TRUE(ofType(to_first_, proto::Message::Hello).empty());
  EXPECT_EQ(player_->counters().resumes, 0u);
}

// The gateway stays dead: after a second of Hellos it tries the next it knows, and plays
// through whichever welcomes it.
TEST_F(SimPlayerResumeTest, ItMovesOnToTheNextGatewayItKnows) {
  start();
  play();
  advance(1100);  // silent a second: resuming at the first gateway
  ASSERT_FALSE(ofType(to_first_, proto::Message::Hello).empty());
  ASSERT_TRUE(to_second_.empty());
  advance(1000);
  std::vector<Sent> hellos = ofType(to_second_, proto::Message::Hello);
  ASSERT_FALSE(hellos.empty()) << "the fallback asked after a second";
  EXPECT_EQ(hellos[0].resume, kResumeToken);
  welcome(second_, hellos.back().nonce, kToken + 2, 0);
  ASSERT_TRUE(player_->welcomed());
  EXPECT_EQ(player_->gateway(), Endpoint::loopback(second_.localPort()));
  to_first_.clear();
  to_second_.clear();
  advance(100);
  EXPECT_TRUE(to_first_.empty());
  EXPECT_FALSE(ofType(to_second_, proto::Message::Input).empty());
}

// Nobody takes it back (its avatar was removed, or the token is refused): it starts over as a
// new player, its inputs numbered from 1 again.
TEST_F(SimPlayerResumeTest, AResumeNobodyAnswersStartsOver) {
  start(/*give_up_s=*/2);
  play();
  advance(3300);
  EXPECT_EQ(player_->counters().resume_failed, 1u);
  std::vector<Sent> hellos = ofType(to_first_, proto::Message::Hello);
  hellos.insert(hellos.end(), to_second_.begin(), to_second_.end());
  ASSERT_FALSE(hellos.empty());
  to_first_.clear();
  to_second_.clear();
  advance(600);
  std::vector<Sent> fresh = ofType(to_first_, proto::Message::Hello);
  std::vector<Sent> more = ofType(to_second_, proto::Message::Hello);
  fresh.insert(fresh.end(), more.begin(), more.end());
  ASSERT_FALSE(fresh.empty());
  EXPECT_TRUE(fresh.back().resume.empty()) << "a new player's Hello";
  gateway::UdpSocket& at = ofType(to_first_, proto::Message::Hello).empty() ? second_ : first_;
  welcome(at, fresh.back().nonce, kToken + 3, 0);
  ASSERT_TRUE(player_->welcomed());
  to_first_.clear();
  to_second_.clear();
  advance(60);
  std::vector<Sent> inputs = ofType(at.localPort() == first_.localPort() ? to_first_ : to_second_,
                                    proto::Message::Input);
  ASSERT_FALSE(inputs.empty());
  EXPECT_EQ(inputs[0].seq, 1u);
  EXPECT_EQ(player_->counters().resumes, 0u);
}

}  // namespace
}  // namespace zonesim::clients
