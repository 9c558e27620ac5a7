#include "wire/impairment.h"

#include <algorithm>
#include <climits>
#include <stdexcept>

#include "common/splitmix.h"

namespace zonesim::gateway {

ImpairmentSettings injectedImpairment(double loss, double delay_ms, double jitter_ms) {
  ImpairmentSettings s;
  s.out.name = s.in.name = "inject";
  s.out.loss_good = s.in.loss_good = loss;
  s.out.delay_ms = delay_ms;
  if (jitter_ms > 0) {
    s.out.jitter = JitterShape::Uniform;
    s.out.jitter_ms = jitter_ms;
    s.out.keep_order = false;
  }
  return s;
}

Impairment::Impairment(const ImpairmentSettings& s, std::uint64_t stream)
    : s_(s), active_(s.active()), stream_(stream), in_link_(s.in, s.seed, splitmix64(stream) ^ 1) {
  validateLinkProfile(s_.out);
}

LinkModel& Impairment::outLink(const Endpoint& to) {
  auto it = out_links_.find(to);
  if (it != out_links_.end()) return it->second;
  // Streams by order of first use, so a run's fates do not depend on ephemeral port numbers.
  std::uint64_t stream = splitmix64(stream_ + 2 * (out_links_.size() + 1));
  return out_links_.try_emplace(to, s_.out, s_.seed, stream).first->second;
}

void Impairment::hold(HeldQueue& q, const Fate& fate, const Endpoint& peer,
                      std::span<const std::uint8_t> bytes) {
  for (int c = 0; c < fate.copies; ++c) {
    const Delivery& d = fate.delivery[std::size_t(c)];
    Held h{d.due_ns, order_++, peer, std::vector<std::uint8_t>(bytes.begin(), bytes.end())};
    if (d.flip_bit >= 0)
      h.bytes[std::size_t(d.flip_bit / 8)] ^= std::uint8_t(1u << (d.flip_bit % 8));
    q.push(std::move(h));
  }
}

bool Impairment::send(UdpSocket& socket, const Endpoint& to, std::span<const std::uint8_t> bytes,
                      std::int64_t now_ns) {
  Fate fate = outLink(to).offer(bytes.size(), now_ns);
  if (fate.copies == 0) return true;  // "sent": the network lost it
  bool at_once = fate.copies == 1 && fate.delivery[0].due_ns <= now_ns &&
                 fate.delivery[0].flip_bit < 0 && outbound_.empty();
  if (at_once) return socket.sendTo(to, bytes);
  hold(outbound_, fate, to, bytes);
  return true;
}

int Impairment::flush(UdpSocket& socket, std::int64_t now_ns) {
  int refused = 0;
  while (!outbound_.empty() && outbound_.top().due_ns <= now_ns) {
    if (!socket.sendTo(outbound_.top().peer, outbound_.top().bytes)) ++refused;
    outbound_.pop();
  }
  return refused;
}

void Impairment::receive(std::span<const std::uint8_t> bytes, const Endpoint& from,
                         std::int64_t now_ns) {
  hold(inbound_, in_link_.offer(bytes.size(), now_ns), from, bytes);
}

bool Impairment::dropIncoming() {
  if (!s_.in.lossOnly())
    throw std::logic_error("dropIncoming: the incoming profile '" + s_.in.name +
                           "' does more than lose datagrams; use receive() and deliver()");
  Fate fate = in_link_.offer(0, 0);
  return fate.copies == 0;
}

std::int64_t Impairment::nextOutgoingDueNs() const {
  return outbound_.empty() ? INT64_MAX : outbound_.top().due_ns;
}

std::int64_t Impairment::nextDueNs() const {
  std::int64_t out = nextOutgoingDueNs();
  std::int64_t in = inbound_.empty() ? INT64_MAX : inbound_.top().due_ns;
  return std::min(out, in);
}

ImpairmentCounters Impairment::counters() const {
  ImpairmentCounters c;
  for (const auto& [to, link] : out_links_) c.out += link.counters();
  c.in = in_link_.counters();
  return c;
}

}  // namespace zonesim::gateway
