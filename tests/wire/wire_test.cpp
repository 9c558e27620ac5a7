// The FlatBuffers datagrams' checks against crafted bytes (the lean downlink frames have their
// own tests: downlink_frame_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/rng.h"
#include "wire/datagram_checksum.h"
#include "wire/wire_encode.h"
#include "wire/wire_verify.h"

namespace zonesim::gateway {
namespace {

// A datagram body (no trailer) with its checksum appended, so the checks behind it see it.
Bytes sealed(Bytes body) {
  appendChecksum(body);
  return body;
}
// The body of an encoded datagram, without its checksum.
Bytes bodyOf(const Bytes& b) {
  return Bytes(b.begin(), b.end() - long(kChecksumBytes));
}

DropReason reasonOf(const Bytes& b, Direction d = Direction::ToGateway) {
  Verified v = verifyDatagram(b, d);
  EXPECT_FALSE(v.ok());
  return v.reason;
}

Bytes batchOf(std::uint16_t count, std::vector<std::uint8_t> packed) {
  flatbuffers::FlatBufferBuilder fbb;
  auto v = fbb.CreateVector(packed);
  proto::FinishDatagramBuffer(
      fbb, proto::CreateDatagram(fbb, 3, proto::Message::StateBatch,
                                 proto::CreateStateBatch(fbb, 1, count, v).Union()));
  return sealed(Bytes(fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize()));
}

TEST(Wire, ValidHelloAndInputPass) {
  EXPECT_TRUE(verifyDatagram(encodeHello(7, "p"), Direction::ToGateway).ok());
  EXPECT_TRUE(verifyDatagram(encodeInput(9, 1, 0.6f, 0.8f), Direction::ToGateway).ok());
  EXPECT_TRUE(verifyDatagram(encodePing(9, 1), Direction::ToGateway).ok());
  EXPECT_TRUE(verifyDatagram(encodeBye(9), Direction::ToGateway).ok());
}

TEST(Wire, GarbageIsMalformedOrBadIdentifier) {
  Bytes garbage(64);
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = std::uint8_t(i * 37 + 11);
  EXPECT_EQ(reasonOf(garbage), DropReason::BadChecksum);
  DropReason r = reasonOf(sealed(garbage));
  EXPECT_TRUE(r == DropReason::BadIdentifier || r == DropReason::Malformed);
  // Garbage that happens to carry the identifier still fails the Verifier.
  garbage[4] = 'Z', garbage[5] = 'S', garbage[6] = 'C', garbage[7] = 'P';
  EXPECT_EQ(reasonOf(sealed(garbage)), DropReason::Malformed);
}

TEST(Wire, TruncatedBuffers) {
  Bytes hello = encodeHello(7, "a somewhat longer player name");
  EXPECT_EQ(reasonOf(Bytes(hello.begin(), hello.begin() + 5)), DropReason::Truncated);
  EXPECT_EQ(reasonOf(Bytes{}), DropReason::Truncated);
  Bytes half(hello.begin(), hello.begin() + long(hello.size() / 2));
  EXPECT_EQ(reasonOf(half), DropReason::BadChecksum);
  EXPECT_EQ(reasonOf(sealed(half)), DropReason::Malformed);
}

TEST(Wire, WrongFileIdentifier) {
  Bytes b = bodyOf(encodeHello(7, "p"));
  b[4] = 'X';
  EXPECT_EQ(reasonOf(sealed(b)), DropReason::BadIdentifier);
}

TEST(Wire, OversizeDatagram) {
  Bytes b = encodeHello(7, "p");
  b.resize(kMaxDatagramBytes + 1);
  EXPECT_EQ(reasonOf(b), DropReason::TooLarge);
}

TEST(Wire, OutOfRangeValues) {
  EXPECT_EQ(reasonOf(encodeInput(9, 1, 1.0f, 1.0f)), DropReason::OutOfRange);
  float nan = std::numeric_limits<float>::quiet_NaN();
  float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(reasonOf(encodeInput(9, 1, nan, 0)), DropReason::OutOfRange);
  EXPECT_EQ(reasonOf(encodeInput(9, 1, 0, inf)), DropReason::OutOfRange);
  EXPECT_EQ(reasonOf(encodeInput(9, 0, 0, 0)), DropReason::OutOfRange);  // seq starts at 1
  EXPECT_EQ(reasonOf(encodeHello(0, "p")), DropReason::OutOfRange);
  EXPECT_EQ(reasonOf(encodeHello(1, std::string(kMaxNameBytes + 1, 'n'))), DropReason::OutOfRange);
}

TEST(Wire, DirectionDecidesWhichMessagesAreAccepted) {
  EXPECT_EQ(reasonOf(encodePong(1, 2, 3)), DropReason::UnexpectedType);
  EXPECT_EQ(reasonOf(encodeHello(1, "p"), Direction::ToClient), DropReason::UnexpectedType);
  EXPECT_TRUE(verifyDatagram(encodePong(1, 2, 3), Direction::ToClient).ok());
}

// An Input carries the inputs before it again: they come back in order, and any that is not
// before it, not in order, not a valid move, or one too many is out of range.
TEST(Wire, InputsCarryEarlierOnesChecked) {
  std::vector<InputRecord> earlier{{4, 0.5f, 0}, {5, 0, -0.5f}, {6, 0.6f, 0.8f}};
  Bytes b = encodeInput(9, 7, 0, 1, 0, 0, earlier);
  Verified v = verifyDatagram(b, Direction::ToGateway);
  ASSERT_TRUE(v.ok());
  const auto* got = v.datagram->msg_as_Input()->earlier();
  ASSERT_NE(got, nullptr);
  ASSERT_EQ(got->size(), 3u);
  EXPECT_EQ(got->Get(0)->seq(), 4u);
  EXPECT_EQ(got->Get(2)->move_z(), 0.8f);
  EXPECT_EQ(verifyDatagram(encodeInput(9, 7, 0, 1), Direction::ToGateway).datagram->msg_as_Input()->earlier(),
            nullptr) << "none: not written";
  std::vector<std::vector<InputRecord>> bad{
      {{20, 0, 0}},                  // not before the input
      {{5, 0, 0}, {4, 0, 0}},        // not in order
      {{0, 0, 0}},                   // seq 0
      {{5, 1, 1}},                   // |move| > 1
      std::vector<InputRecord>(kMaxEarlierInputs + 1, {1, 0, 0}),
  };
  for (std::size_t i = 0; i < kMaxEarlierInputs + 1; ++i) bad.back()[i].seq = std::uint32_t(i + 1);
  for (const auto& e : bad)
    EXPECT_EQ(reasonOf(encodeInput(9, 20, 0, 1, 0, 0, e)), DropReason::OutOfRange)
        << "first earlier seq " << e.front().seq << ", " << e.size() << " of them";
}

// The leaderboard's query and answer: one way each, the rows back in order, a query for 0 or
// more than a datagram holds refused, an answer cut to what the check allows.
TEST(Wire, LeaderboardQueriesAndAnswersAreChecked) {
  EXPECT_TRUE(verifyDatagram(encodeLeaderboardQuery(9, 10), Direction::ToGateway).ok());
  EXPECT_EQ(reasonOf(encodeLeaderboardQuery(9, 0)), DropReason::OutOfRange);
  EXPECT_EQ(reasonOf(encodeLeaderboardQuery(9, kMaxLeaderboardRows + 1)), DropReason::OutOfRange);
  EXPECT_EQ(reasonOf(encodeLeaderboardQuery(9, 10), Direction::ToClient), DropReason::UnexpectedType);
  std::vector<LeaderboardLine> rows{{7, 900, 30}, {3, 800, 12}};
  Bytes b = encodeLeaderboard(9, rows, "");
  Verified v = verifyDatagram(b, Direction::ToClient);
  ASSERT_TRUE(v.ok());
  const proto::Leaderboard* l = v.datagram->msg_as_Leaderboard();
  ASSERT_EQ(l->rows()->size(), 2u);
  EXPECT_EQ(l->rows()->Get(1)->player(), 3u);
  EXPECT_EQ(l->rows()->Get(0)->score(), 900);
  EXPECT_EQ(l->reason(), nullptr);
  EXPECT_EQ(reasonOf(b), DropReason::UnexpectedType);
  std::vector<LeaderboardLine> many(kMaxLeaderboardRows + 5, {1, 1, 1});
  Bytes cut = encodeLeaderboard(9, many, "");
  Verified c = verifyDatagram(cut, Direction::ToClient);
  ASSERT_TRUE(c.ok()) << "at most kMaxLeaderboardRows go, and they fit a datagram";
  EXPECT_EQ(c.datagram->msg_as_Leaderboard()->rows()->size(), kMaxLeaderboardRows);
}

// The reliable channel's two messages: each field comes back, each goes one way only, and a
// sequence 0, an unknown kind or status or an overlong reason is out of range.
TEST(Wire, TransactionsAndOutcomesRoundTripAndAreChecked) {
  TransactionInfo t{7, 3, 901, -2, 5, 45, 0, 6};
  Bytes tb = encodeTransaction(9, t);  // the Verified points into it
  Verified v = verifyDatagram(tb, Direction::ToGateway);
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v.datagram->token(), 9u);
  EXPECT_EQ(transactionInfo(*v.datagram->msg_as_Transaction()), t);
  EXPECT_EQ(reasonOf(encodeTransaction(9, t), Direction::ToClient), DropReason::UnexpectedType);
  TransactionInfo decided_itself{3, 2};
  decided_itself.decided = 3;  // a client cannot hold the outcome of what it is still sending
  for (TransactionInfo bad :
       {TransactionInfo{0, 2}, TransactionInfo{1, 0}, TransactionInfo{1, 5}, decided_itself})
    EXPECT_EQ(reasonOf(encodeTransaction(9, bad)), DropReason::OutOfRange)
        << "seq " << bad.seq << " kind " << int(bad.kind);

  Bytes ob = encodeTransactionOutcome(9, 7, 3, "database unavailable");
  Verified o = verifyDatagram(ob, Direction::ToClient);
  ASSERT_TRUE(o.ok());
  const proto::TransactionOutcome* out = o.datagram->msg_as_TransactionOutcome();
  EXPECT_EQ(out->seq(), 7u);
  EXPECT_EQ(out->status(), 3u);
  EXPECT_EQ(out->reason()->str(), "database unavailable");
  EXPECT_EQ(reasonOf(encodeTransactionOutcome(9, 7, 0, "")), DropReason::UnexpectedType);
  EXPECT_EQ(reasonOf(encodeTransactionOutcome(9, 0, 0, ""), Direction::ToClient),
            DropReason::OutOfRange);
  EXPECT_EQ(reasonOf(encodeTransactionOutcome(9, 7, 4, ""), Direction::ToClient),
            DropReason::OutOfRange);
  // The encoder cuts a reason to what the check allows.
  Bytes long_reason = encodeTransactionOutcome(9, 7, 3, std::string(kMaxReasonBytes + 40, 'r'));
  Verified cut = verifyDatagram(long_reason, Direction::ToClient);
  ASSERT_TRUE(cut.ok());
  EXPECT_EQ(cut.datagram->msg_as_TransactionOutcome()->reason()->size(), kMaxReasonBytes);
}

TEST(Wire, EmptyUnionIsNoMessage) {
  flatbuffers::FlatBufferBuilder fbb;
  proto::FinishDatagramBuffer(fbb, proto::CreateDatagram(fbb, 5));
  Bytes b(fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize());
  EXPECT_EQ(reasonOf(sealed(b)), DropReason::NoMessage);
}

TEST(Wire, StatesAsFlatBuffersAreRefused) {
  // StateBatch, Spawn and Despawn travel as lean frames only: one path, one set of checks.
  EXPECT_EQ(reasonOf(batchOf(1, {1, 2, 3}), Direction::ToClient), DropReason::UnexpectedType);
  flatbuffers::FlatBufferBuilder fbb;
  std::vector<std::uint64_t> ids{4};
  auto v = fbb.CreateVector(ids);
  proto::FinishDatagramBuffer(fbb, proto::CreateDatagram(fbb, 3, proto::Message::Despawn,
                                                         proto::CreateDespawn(fbb, 1, v).Union()));
  Bytes despawn = sealed(Bytes(fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize()));
  EXPECT_EQ(reasonOf(despawn, Direction::ToClient), DropReason::UnexpectedType);
}

TEST(Wire, WelcomeWithAnUnusableCodecIsRejected) {
  WelcomeInfo w;
  w.token = 3;
  w.world_max = proto::Vec3f(1, 1, 1);
  EXPECT_TRUE(verifyDatagram(encodeWelcome(w), Direction::ToClient).ok());
  w.codec.cell_size = 0;
  EXPECT_EQ(reasonOf(encodeWelcome(w), Direction::ToClient), DropReason::OutOfRange);
  w.codec = {};
  w.codec.rotation_bits = 40;
  EXPECT_EQ(reasonOf(encodeWelcome(w), Direction::ToClient), DropReason::OutOfRange);
  w.codec = {};
  w.codec.position_resolution = std::nanf("");
  EXPECT_EQ(reasonOf(encodeWelcome(w), Direction::ToClient), DropReason::OutOfRange);
  w.codec = {};
  w.sim_dt = 0;
  EXPECT_EQ(reasonOf(encodeWelcome(w), Direction::ToClient), DropReason::OutOfRange);
}

// Corrupted Welcomes and Handoffs: the client-side check never reads out of bounds, and a
// Welcome that passes announces a codec and clock a client can work with.
TEST(Wire, CorruptedClientBoundDatagramsNeverPassBadValues) {
  WelcomeInfo w;
  w.token = 3;
  w.world_max = proto::Vec3f(1, 1, 1);
  std::vector<Bytes> seeds{encodeWelcome(w), encodeHandoff(3, {1, 0, 1, 2, 3})};
  Pcg32 rng(77, 3);
  int passed = 0;
  for (int i = 0; i < 20000; ++i) {
    Bytes b = bodyOf(seeds[rng.next() % seeds.size()]);
    for (int f = 0; f < 3; ++f) b[rng.next() % b.size()] = std::uint8_t(rng.next());
    b = sealed(b);
    Verified v = verifyDatagram(b, Direction::ToClient);
    if (!v.ok()) continue;
    ++passed;
    if (const proto::Welcome* m = v.datagram->msg_as_Welcome()) {
      EXPECT_TRUE(validCodec(*m->codec()));
      EXPECT_TRUE(std::isfinite(m->tick_rate()) && m->tick_rate() > 0);
      EXPECT_NE(m->token(), 0u);
    } else if (const proto::Handoff* h = v.datagram->msg_as_Handoff()) {
      EXPECT_GE(h->to_zone(), 0);
      EXPECT_NE(h->avatar_id(), 0u);
    }
  }
  EXPECT_GT(passed, 0) << "some corruptions only touch values that stay in range";
}

}  // namespace
}  // namespace zonesim::gateway
