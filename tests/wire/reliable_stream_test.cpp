// The reliable stream on a simulated link that drops 19% of datagrams each way, delays each by
// 20-60 ms (so they overtake each other) and repeats 2%: 10,000 messages arrive exactly once and
// in order, whatever the loss; a receiver restored from its durable point gets everything after
// it again; the retransmission timeout follows the round trip and backs off; a full window and a
// forged acknowledgement change nothing.
#include "wire/reliable_stream.h"

#include <gtest/gtest.h>

#include <map>

#include "common/rng.h"

namespace zonesim::gateway {
namespace {

constexpr std::int64_t kMs = 1'000'000;

std::vector<std::uint8_t> payloadOf(std::uint32_t n) {
  return {std::uint8_t(n), std::uint8_t(n >> 8), std::uint8_t(n >> 16), std::uint8_t(n >> 24)};
}
std::uint32_t valueOf(std::span<const std::uint8_t> p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
         std::uint32_t(p[3]) << 24;
}

// One direction of the link: datagrams due at a time, lost, late or twice.
template <typename T>
struct LossyPipe {
  explicit LossyPipe(std::uint64_t seed) : rng(seed, 0x11) {}
  void send(std::int64_t now_ns, T item) {
    if (rng.uniform() < 0.19) return;
    int copies = rng.uniform() < 0.02 ? 2 : 1;
    for (int i = 0; i < copies; ++i)
      in_flight.emplace(now_ns + std::int64_t((20 + 40 * rng.uniform()) * kMs), item);
  }
  std::vector<T> arrived(std::int64_t now_ns) {
    std::vector<T> out;
    while (!in_flight.empty() && in_flight.begin()->first <= now_ns) {
      out.push_back(in_flight.begin()->second);
      in_flight.erase(in_flight.begin());
    }
    return out;
  }
  Pcg32 rng;
  std::multimap<std::int64_t, T> in_flight;
};

struct Message {
  std::uint32_t seq;
  std::vector<std::uint8_t> payload;
};
struct Ack {
  std::uint32_t cumulative, echo;
};

// Sender and receiver joined by two lossy pipes, on a 1 ms virtual clock. The receiver
// acknowledges `durable()`: what it delivered, or less when it acks only what it saved.
struct Link {
  explicit Link(std::uint64_t seed) : data(seed), acks(seed + 1) {}

  void step(const std::function<void(std::uint32_t, std::span<const std::uint8_t>)>& deliver,
            const std::function<std::uint32_t()>& durable) {
    now += kMs;
    sender.sendDue(now, [&](std::uint32_t seq, std::span<const std::uint8_t> p) {
      data.send(now, Message{seq, {p.begin(), p.end()}});
      ++datagrams;
    });
    for (const Message& m : data.arrived(now)) {
      receiver->receive(m.seq, m.payload, deliver);
      acks.send(now, Ack{durable(), m.seq});
    }
    for (const Ack& a : acks.arrived(now)) sender.acknowledge(a.cumulative, now, a.echo);
  }

  std::int64_t now = 0;
  ReliableSender sender;
  std::unique_ptr<ReliableReceiver> receiver = std::make_unique<ReliableReceiver>();
  LossyPipe<Message> data;
  LossyPipe<Ack> acks;
  std::uint64_t datagrams = 0;
};

TEST(ReliableStream, TenThousandMessagesExactlyOnceInOrderUnderLossEachWay) {
  constexpr std::uint32_t kMessages = 10'000;
  Link link(7);
  std::vector<std::uint32_t> got;
  auto deliver = [&](std::uint32_t seq, std::span<const std::uint8_t> p) {
    EXPECT_EQ(valueOf(p), seq * 3) << "the payload sent under its seq";
    got.push_back(seq);
  };
  std::uint32_t pushed = 0;
  for (int t = 0; t < 600'000 && (pushed < kMessages || link.sender.inFlight() > 0); ++t) {
    // A few messages a tick while the window has room.
    for (int i = 0; i < 2 && pushed < kMessages; ++i) {
      if (!link.sender.push(payloadOf((pushed + 1) * 3))) break;
      ++pushed;
    }
    link.step(deliver, [&] { return link.receiver->delivered(); });
  }
  ASSERT_EQ(got.size(), kMessages) << "each delivered once";
  for (std::uint32_t i = 0; i < kMessages; ++i) ASSERT_EQ(got[i], i + 1) << "in order";
  EXPECT_EQ(link.sender.inFlight(), 0u);
  EXPECT_EQ(link.sender.acknowledged(), kMessages);
  EXPECT_GT(link.sender.retransmissions(), kMessages / 10) << "the loss was real";
  EXPECT_GT(link.receiver->duplicates(), 0u);
  EXPECT_EQ(link.receiver->held(), 0u);
}

// A receiver that acknowledges only what it made durable (a zone: committed), and crashes
// between two such points: the restored receiver knows only the last, and the consumer is
// rewound to it. The sender resends everything after it; every message ends applied once.
TEST(ReliableStream, ARestoredReceiverGetsEverythingAfterItsDurablePoint) {
  constexpr std::uint32_t kMessages = 3'000;
  Link link(11);
  std::vector<std::uint32_t> applied, saved;
  std::uint32_t saved_delivered = 0;
  auto deliver = [&](std::uint32_t seq, std::span<const std::uint8_t>) { applied.push_back(seq); };
  std::uint32_t pushed = 0;
  int restarts = 0;
  for (int t = 0; t < 600'000 && (pushed < kMessages || link.sender.inFlight() > 0); ++t) {
    if (pushed < kMessages && link.sender.push(payloadOf(pushed + 1))) ++pushed;
    link.step(deliver, [&] { return saved_delivered; });
    if (t % 20 == 19) {  // a commit, acknowledged at once: what it saved is durable
      saved = applied;
      saved_delivered = link.receiver->delivered();
      link.acks.send(link.now, Ack{saved_delivered, 0});
    }
    if (t % 1500 == 1400) {  // a crash between two durable points: back to the last one
      applied = saved;
      link.receiver = std::make_unique<ReliableReceiver>(saved_delivered);
      link.sender.resendAll();
      ++restarts;
    }
  }
  ASSERT_GE(restarts, 2);
  ASSERT_EQ(applied.size(), kMessages) << "delivered " << link.receiver->delivered() << " acked "
                                       << link.sender.acknowledged() << " pushed " << pushed;
  for (std::uint32_t i = 0; i < kMessages; ++i) ASSERT_EQ(applied[i], i + 1);
}

TEST(ReliableStream, AFullWindowRefusesAndAnAckMakesRoom) {
  ReliableSender s({.window = 3});
  EXPECT_EQ(s.push({1}), 1u);
  EXPECT_EQ(s.push({2}), 2u);
  EXPECT_EQ(s.push({3}), 3u);
  EXPECT_EQ(s.push({4}), std::nullopt);
  s.sendDue(0, [](std::uint32_t, std::span<const std::uint8_t>) {});
  s.acknowledge(2, kMs);
  EXPECT_EQ(s.inFlight(), 1u);
  EXPECT_EQ(s.push({4}), 4u);
}

TEST(ReliableStream, AStaleOrForgedAckChangesNothing) {
  ReliableSender s;
  for (std::uint8_t i = 1; i <= 4; ++i) s.push({i});
  s.sendDue(0, [](std::uint32_t, std::span<const std::uint8_t>) {});
  s.acknowledge(2, kMs);
  s.acknowledge(1, kMs);  // older: ignored
  EXPECT_EQ(s.acknowledged(), 2u);
  s.acknowledge(1'000'000, kMs);  // beyond anything pushed: only what was sent counts
  EXPECT_EQ(s.acknowledged(), 4u);
  EXPECT_EQ(s.inFlight(), 0u);
  EXPECT_EQ(s.push({5}), 5u) << "numbering goes on after the last pushed";
}

TEST(ReliableStream, TheTimeoutFollowsTheRoundTripAndBacksOff) {
  ReliableSender s({.window = 64, .initial_rto_ns = 250 * kMs, .min_rto_ns = 50 * kMs,
                    .max_rto_ns = 2000 * kMs});
  std::int64_t now = 0;
  auto none = [](std::uint32_t, std::span<const std::uint8_t>) {};
  for (int i = 0; i < 40; ++i) {  // a steady 100 ms round trip
    std::uint32_t seq = *s.push({1});
    s.sendDue(now, none);
    now += 100 * kMs;
    s.acknowledge(seq, now, seq);
  }
  EXPECT_GE(s.rtoNs(), 100 * kMs);
  EXPECT_LE(s.rtoNs(), 130 * kMs) << "SRTT with little variance";
  // Lost: resent after the timeout, then after twice it.
  std::int64_t rto = s.rtoNs();
  s.push({2});
  EXPECT_EQ(s.sendDue(now, none), 1u);
  EXPECT_EQ(s.sendDue(now + rto - 1, none), 0u);
  EXPECT_EQ(s.sendDue(now + rto, none), 1u);
  EXPECT_EQ(s.rtoNs(), 2 * rto);
  EXPECT_EQ(s.sendDue(now + rto + 2 * rto - 1, none), 0u);
  EXPECT_EQ(s.sendDue(now + 3 * rto, none), 1u);
  EXPECT_EQ(s.retransmissions(), 2u);
  // An ack of nothing new leaves the backoff.
  s.acknowledge(s.lastPushed() - 1, now + 3 * rto + 5 * kMs, 0);
  EXPECT_EQ(s.rtoNs(), 4 * rto);
  // Its ack answers either copy: no sample (Karn); but new data acknowledged ends the backoff,
  // so the timeout is the estimate's again.
  s.acknowledge(s.lastPushed(), now + 3 * rto + 10 * kMs, s.lastPushed());
  EXPECT_EQ(s.rtoNs(), rto);
}

// Before any sample, the end of a backoff goes back to the initial timeout.
TEST(ReliableStream, AnAckWithoutASampleEndsTheBackoffAtTheInitialTimeout) {
  ReliableSender s({.window = 8, .initial_rto_ns = 250 * kMs, .min_rto_ns = 50 * kMs,
                    .max_rto_ns = 2000 * kMs});
  auto none = [](std::uint32_t, std::span<const std::uint8_t>) {};
  s.push({1});
  s.sendDue(0, none);
  s.sendDue(250 * kMs, none);
  EXPECT_EQ(s.rtoNs(), 500 * kMs);
  s.acknowledge(1, 300 * kMs, 1);  // resent: no sample
  EXPECT_EQ(s.rtoNs(), 250 * kMs);
}

// A receiver that answers later messages but not an earlier one (a zone holding later
// transactions for a gap) lets the sender resend the earlier one at once, once a round trip.
TEST(ReliableStream, AnExpeditedMessageGoesAtTheNextSendNotAtItsTimeout) {
  ReliableSender s({.window = 8, .initial_rto_ns = 250 * kMs, .min_rto_ns = 50 * kMs,
                    .max_rto_ns = 2000 * kMs});
  std::vector<std::uint32_t> sent;
  auto record = [&](std::uint32_t seq, std::span<const std::uint8_t>) { sent.push_back(seq); };
  // Round trips of 60 and 140 ms in turn learnt first: SRTT about 100 ms, RTO well above.
  for (int i = 0; i < 20; ++i) {
    std::uint32_t seq = *s.push({1});
    s.sendDue(std::int64_t(i) * 200 * kMs, record);
    s.acknowledge(seq, std::int64_t(i) * 200 * kMs + (i % 2 ? 140 : 60) * kMs, seq);
  }
  ASSERT_GT(s.rtoNs(), 200 * kMs);
  std::int64_t now = 4000 * kMs;
  std::uint32_t lost = *s.push({2});
  s.push({3});
  sent.clear();
  EXPECT_EQ(s.sendDue(now, record), 2u);
  s.expedite(lost, now + 50 * kMs);  // within a round trip of its copy: its answer may come
  EXPECT_EQ(s.sendDue(now + 50 * kMs, record), 0u);
  s.expedite(lost, now + 110 * kMs);
  EXPECT_EQ(s.sendDue(now + 110 * kMs, record), 1u) << "before its timeout of " << s.rtoNs();
  EXPECT_EQ(sent.back(), lost);
  EXPECT_EQ(s.retransmissions(), 1u);
  s.expedite(99, now + 500 * kMs);  // never pushed: nothing
  s.expedite(lost - 1, now + 500 * kMs);  // acknowledged: nothing
  EXPECT_EQ(s.retransmissions(), 1u);
}

TEST(ReliableStream, TheReceiverHoldsEarlyMessagesWithinItsWindowOnly) {
  ReliableReceiver r(0, 4);
  std::vector<std::uint32_t> got;
  auto deliver = [&](std::uint32_t seq, std::span<const std::uint8_t>) { got.push_back(seq); };
  std::vector<std::uint8_t> p{0};
  EXPECT_EQ(r.receive(3, p, deliver), Arrival::Held);
  EXPECT_EQ(r.receive(5, p, deliver), Arrival::TooFar);
  EXPECT_EQ(r.receive(3, p, deliver), Arrival::Duplicate);
  EXPECT_EQ(r.receive(2, p, deliver), Arrival::Held);
  EXPECT_EQ(r.receive(1, p, deliver), Arrival::Delivered);
  EXPECT_EQ(got, (std::vector<std::uint32_t>{1, 2, 3}));
  EXPECT_EQ(r.delivered(), 3u);
  EXPECT_EQ(r.receive(2, p, deliver), Arrival::Duplicate);
  EXPECT_EQ(r.held(), 0u);
}

}  // namespace
}  // namespace zonesim::gateway
