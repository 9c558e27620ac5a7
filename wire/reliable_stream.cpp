#include "wire/reliable_stream.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace zonesim::gateway {

ReliableSender::ReliableSender(const ReliableSenderOptions& options)
    : options_(options), rto_ns_(options.initial_rto_ns) {}

std::optional<std::uint32_t> ReliableSender::push(std::vector<std::uint8_t> payload) {
  if (unacked_.size() >= options_.window) return std::nullopt;
  std::uint32_t seq = next_seq_++;
  unacked_.push_back({seq, std::move(payload)});
  return seq;
}

std::size_t ReliableSender::sendDue(
    std::int64_t now_ns,
    const std::function<void(std::uint32_t, std::span<const std::uint8_t>)>& send) {
  std::size_t sent = 0;
  bool head_timed_out = false;
  for (Pending& p : unacked_) {
    bool fresh = p.last_sent_ns < 0;
    if (!fresh && now_ns - p.last_sent_ns < rto_ns_) continue;
    if (!fresh) {
      p.resent = true;
      ++retransmissions_;
      head_timed_out |= &p == &unacked_.front();
    } else {
      p.first_sent_ns = now_ns;
    }
    p.last_sent_ns = now_ns;
    send(p.seq, p.payload);
    ++sent;
  }
  // Back off as TCP's one timer does: when the oldest message times out. Each message has its
  // own timer, so later ones expiring in turn must not double the timeout once each.
  if (head_timed_out) rto_ns_ = std::min(options_.max_rto_ns, rto_ns_ * 2);
  return sent;
}

void ReliableSender::acknowledge(std::uint32_t cumulative, std::int64_t now_ns, std::uint32_t echo) {
  // The round trip of the message whose arrival the ack answers, if it was sent once (Karn):
  // not of the newest one the cumulative ack covers, which may have waited at the receiver
  // for an earlier one's resend and would teach the timeout that wait.
  if (echo != 0 && !unacked_.empty() && echo >= unacked_.front().seq) {
    std::size_t i = echo - unacked_.front().seq;
    if (i < unacked_.size() && !unacked_[i].resent && unacked_[i].first_sent_ns >= 0) {
      rtt_.sample(double(now_ns - unacked_[i].first_sent_ns) * 1e-9);
      rto_ns_ = std::int64_t(
          rtt_.rtoS(options_.min_rto_ns * 1e-9, options_.max_rto_ns * 1e-9, 0) * 1e9);
    }
  }
  // An ack beyond anything pushed is a confused or forged peer: only what was sent counts.
  cumulative = std::min(cumulative, next_seq_ - 1);
  if (cumulative <= acked_) return;
  acked_ = cumulative;
  while (!unacked_.empty() && unacked_.front().seq <= cumulative) unacked_.pop_front();
  // New data acknowledged: the path works again, so the backoff ends (as Linux does), even
  // without a fresh sample. Else, over a lossy link where most messages get resent, Karn's rule
  // leaves few samples and the doubled timeout would stay for good.
  rto_ns_ = std::int64_t(rtt_.rtoS(options_.min_rto_ns * 1e-9, options_.max_rto_ns * 1e-9,
                                    options_.initial_rto_ns * 1e-9) *
                         1e9);
}

void ReliableSender::expedite(std::uint32_t seq, std::int64_t now_ns) {
  if (unacked_.empty() || seq < unacked_.front().seq) return;
  std::size_t i = seq - unacked_.front().seq;
  if (i >= unacked_.size()) return;
  Pending& p = unacked_[i];
  // Not again within a round trip of the last copy: the answer to that one may be on its way.
  auto round_trip = std::int64_t(rtt_.sampled() ? rtt_.srttS() * 1e9 : double(rto_ns_) / 2);
  if (p.last_sent_ns < 0 || now_ns - p.last_sent_ns < round_trip) return;
  p.last_sent_ns = now_ns - rto_ns_;  // due now, and counted as a retransmission when sent
}

void ReliableSender::resendAll() {
  for (Pending& p : unacked_) {
    if (p.last_sent_ns >= 0) p.resent = true;  // its ack may answer either copy
    p.last_sent_ns = -1;
  }
}

std::int64_t ReliableSender::nextDueNs() const {
  std::int64_t due = INT64_MAX;
  for (const Pending& p : unacked_)
    due = std::min(due, p.last_sent_ns < 0 ? INT64_MIN : p.last_sent_ns + rto_ns_);
  return due;
}

ReliableReceiver::ReliableReceiver(std::uint32_t delivered, std::size_t window)
    : delivered_(delivered), window_(window) {}

Arrival ReliableReceiver::receive(
    std::uint32_t seq, std::span<const std::uint8_t> payload,
    const std::function<void(std::uint32_t, std::span<const std::uint8_t>)>& deliver) {
  if (seq <= delivered_ || held_.contains(seq)) {
    ++duplicates_;
    return Arrival::Duplicate;
  }
  if (seq - delivered_ > window_) return Arrival::TooFar;
  if (seq != delivered_ + 1) {
    held_.emplace(seq, std::vector<std::uint8_t>(payload.begin(), payload.end()));
    return Arrival::Held;
  }
  deliver(seq, payload);
  delivered_ = seq;
  for (auto it = held_.begin(); it != held_.end() && it->first == delivered_ + 1;
       it = held_.erase(it)) {
    deliver(it->first, it->second);
    delivered_ = it->first;
  }
  return Arrival::Delivered;
}

}  // namespace zonesim::gateway
