// libFuzzer target: the gateway's datagram handler, fed arbitrary bytes from three addresses,
// one of which owns a live session, raw or with a valid checksum appended (to get past it),
// plus well-formed inputs carrying that session's token with fuzzed values (to reach the range
// checks behind the Verifier). It must never crash, hang or
// trip a sanitizer; every datagram is either accepted or dropped and counted.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>

#include "gateway/datagram_handler.h"
#include "gateway/session_table.h"
#include "wire/datagram_checksum.h"
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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  Harness& h = *harness();
  const std::uint8_t mode = data[0];
  std::span<const std::uint8_t> rest(data + 1, size - 1);
  const Endpoint& from = (mode & 3) == 0 ? h.player : (mode & 3) == 1 ? h.stranger : h.other;
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
