// libFuzzer target: the gateway's datagram handler, fed arbitrary bytes from three addresses,
// one of which owns a live session, raw or with a valid checksum appended (to get past it),
// plus well-formed inputs carrying that session's token with fuzzed values (to reach the range
// checks behind the Verifier), plus Hellos to a gateway with the cluster key carrying fuzzed
// connect or resume tokens, raw or signed with fuzzed fields (to reach the checks behind the
// tag). And
// the client's side: fuzzed client-bound datagrams through the client's checks, lean frames
// raw or sealed with the session's keyed checksum, their states unpacked by the client's codec.
// It must never crash, hang or trip a sanitizer; every datagram is either accepted or dropped
// and counted.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>

#include "auth/connect_token.h"
#include "auth/resume_token.h"
#include "dr/state_codec.h"
#include "gateway/datagram_handler.h"
#include "gateway/session_table.h"
#include "wire/datagram_checksum.h"
#include "wire/downlink_frame.h"
#include "wire/wire_encode.h"

namespace {

using namespace zonesim;
using namespace zonesim::gateway;

struct Harness {
  SessionTable sessions{1, 64};
  DatagramHandler handler{sessions, HandlerConfig{{{0, 0, 0}, {100, 10, 100}}, 30, 1}};
  Endpoint player = Endpoint::loopback(40001), stranger = Endpoint::loopback(40002),
           other = Endpoint::loopback(40003);
  std::uint64_t token = 0;
  Outbox out;

  Harness() {
    Bytes hello = encodeHello(7, "fuzz");
    handler.handle(hello, player, 0, out);
    SlotHandle h = *sessions.findByToken(firstToken());
    Session* s = sessions.get(h);
    s->welcomed = true;  // as if its avatar had been announced: inputs are accepted
    s->avatar_id = 1;
    s->zone = 0;
    token = s->token;
    out.clear();
  }

  std::uint64_t firstToken() {
    std::uint64_t t = 0;
    sessions.forEach([&](SlotHandle, Session& s) { t = s.token; });
    return t;
  }
};

std::unique_ptr<Harness>& harness() {
  static std::unique_ptr<Harness> h = std::make_unique<Harness>();
  return h;
}

auth::AuthKey fuzzKey() {
  return auth::AuthKey(std::vector<std::uint8_t>(32, 0x5c), "fuzz key");
}

/// A gateway (id 1) that requires connect tokens and takes resume tokens, its clock fixed.
struct KeyedHarness {
  SessionTable sessions{1, 64};
  DatagramHandler handler{sessions, config()};
  Outbox out;

  static HandlerConfig config() {
    HandlerConfig c;
    c.world = {{0, 0, 0}, {100, 10, 100}};
    c.auth_key = fuzzKey();
    c.resume_key = fuzzKey();
    c.gateway_id = 1;
    c.unix_now_ms = [] { return std::uint64_t{1'800'000'000'000}; };
    return c;
  }
};

KeyedHarness& keyed() {
  static KeyedHarness h;
  return h;
}

/// A Hello to the keyed gateway: rest as the token, or a token signed from fields in rest.
void fuzzTokenHello(std::span<const std::uint8_t> rest, bool sign, const Endpoint& from) {
  KeyedHarness& k = keyed();
  if (sign && rest.size() >= 24) {
    auth::ConnectToken t;
    std::memcpy(&t.player_id, rest.data(), 8);
    std::memcpy(&t.expiry_unix_ms, rest.data() + 8, 8);
    std::memcpy(&t.gateway_id, rest.data() + 16, 2);
    std::memcpy(&t.client_port, rest.data() + 18, 2);
    std::memcpy(&t.client_address, rest.data() + 20, 4);
    // Half the time from the address it names, to get past the address check.
    if (rest.size() > 24 && (rest[24] & 1)) {
      t.client_address = from.address;
      t.client_port = from.port;
    }
    auth::TokenBytes b = auth::signToken(t, fuzzKey());
    k.handler.handle(encodeHello(t.player_id | 1, "fuzz", b), from, 0, k.out);
  } else {
    k.handler.handle(encodeHello(7, "fuzz", rest.first(std::min<std::size_t>(rest.size(), 128))),
                     from, 0, k.out);
  }
  k.out.clear();
}

/// A resuming Hello to the keyed gateway: rest as the resume token, or one signed from fields
/// in rest (any player, any kind, any expiry).
void fuzzResumeHello(std::span<const std::uint8_t> rest, bool sign, const Endpoint& from) {
  KeyedHarness& k = keyed();
  if (sign && rest.size() >= 24) {
    auth::ResumeToken t;
    std::memcpy(&t.player_id, rest.data(), 8);
    std::memcpy(&t.expiry_unix_ms, rest.data() + 8, 8);
    t.kind = rest[16];
    std::memcpy(&t.client_port, rest.data() + 18, 2);
    std::memcpy(&t.client_address, rest.data() + 20, 4);
    if (rest.size() > 24 && (rest[24] & 1)) {
      t.client_address = from.address;
      t.client_port = from.port;
    }
    auth::ResumeBytes b = auth::signResume(t, fuzzKey());
    k.handler.handle(encodeHello(t.player_id | 1, "fuzz", {}, 0, b), from, 0, k.out);
  } else {
    k.handler.handle(
        encodeHello(7, "fuzz", {}, 0, rest.first(std::min<std::size_t>(rest.size(), 128))), from,
        0, k.out);
  }
  k.out.clear();
}

/// What a client does with a datagram from its gateway (clients/sim_player.cpp, session token
/// kClientToken): rest raw, or sealed with the keyed checksum to reach the checks behind it.
void fuzzClientBound(std::span<const std::uint8_t> rest, bool seal) {
  constexpr std::uint64_t kClientToken = 0x0123456789abcdefULL;
  static const dr::StateCodec codec{dr::CodecParams{}};
  Bytes bytes(rest.begin(), rest.end());
  if (!isDownlinkFrame(bytes)) {
    verifyDatagram(bytes, Direction::ToClient);
    return;
  }
  if (seal) {
    std::uint8_t key[8];
    for (int i = 0; i < 8; ++i) key[i] = std::uint8_t(kClientToken >> (8 * i));
    std::uint32_t crc = crc32c(key, bytes);
    for (int i = 0; i < 4; ++i) bytes.push_back(std::uint8_t(crc >> (8 * i)));
  }
  ParsedFrame p = parseFrame(bytes, kClientToken);
  if (!p.ok() || p.frame.header.kind == FrameKind::Despawn) return;
  codec.unpack(p.frame.payload, p.frame.header.count, p.frame.header.tick);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  Harness& h = *harness();
  const std::uint8_t mode = data[0];
  std::span<const std::uint8_t> rest(data + 1, size - 1);
  const Endpoint& from = (mode & 3) == 0 ? h.player : (mode & 3) == 1 ? h.stranger : h.other;
  if ((mode & 0xe0) == 0x20) {
    fuzzTokenHello(rest, mode & 0x10, from);
    return 0;
  }
  if ((mode & 0xe0) == 0xa0) {
    fuzzResumeHello(rest, mode & 0x10, from);
    return 0;
  }
  if ((mode & 0xe0) == 0x60) {
    fuzzClientBound(rest, mode & 0x10);
    return 0;
  }
  if ((mode & 0x80) && rest.size() >= 12) {
    // A datagram with the live token and fuzzed values: NaN, infinities, huge moves, any seq.
    std::uint32_t seq;
    float mx, mz;
    std::memcpy(&seq, rest.data(), 4);
    std::memcpy(&mx, rest.data() + 4, 4);
    std::memcpy(&mz, rest.data() + 8, 4);
    Bytes input = encodeInput(h.token, seq, mx, mz);
    h.handler.handle(input, from, std::int64_t(seq), h.out);
  } else if (mode & 0x40) {
    // The fuzzed bytes with a valid checksum appended, to reach the checks behind it.
    Bytes sealed(rest.begin(), rest.end());
    appendChecksum(sealed);
    h.handler.handle(sealed, from, 0, h.out);
  } else {
    h.handler.handle(rest, from, 0, h.out);
  }
  // Keep the live session: a fuzzed Bye must not end the run's only authenticated path.
  bool closed = !h.out.closed.empty();
  h.out.clear();
  if (closed) harness() = std::make_unique<Harness>();
  return 0;
}
