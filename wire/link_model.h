#pragma once
// The fate of each datagram offered to one direction of one link (a LinkProfile), decided with
// a seeded generator and no I/O, so every statistic can be tested against its parameters. In
// order: Gilbert–Elliott loss; the bandwidth cap, which serialises datagrams at rate_kbps
// behind a drop-tail queue of queue_bytes; the base delay plus jitter (FIFO unless keep_order is
// false); reordering (held back by an extra gap, not holding up the ones behind); duplication;
// corruption (one bit flipped in a copy).

#include <array>
#include <cstdint>

#include "common/rng.h"
#include "wire/link_profile.h"

namespace zonesim::gateway {

/// What the model did, per datagram offered.
struct LinkCounters {
  std::uint64_t offered = 0;
  std::uint64_t lost = 0;          ///< Gilbert–Elliott loss
  std::uint64_t tail_dropped = 0;  ///< the cap's queue was full
  std::uint64_t reordered = 0, duplicated = 0, corrupted = 0;
  std::uint64_t delivered = 0;  ///< copies released, duplicates included
  LinkCounters& operator+=(const LinkCounters& o);
};

/// One copy of a datagram to release.
struct Delivery {
  std::int64_t due_ns = 0;
  std::int64_t flip_bit = -1;  ///< the bit to flip (corruption), or -1
};

/// None (lost or dropped), one or two (duplicated) deliveries.
struct Fate {
  int copies = 0;
  std::array<Delivery, 2> delivery{};
};

class LinkModel {
 public:
  /// Validates the profile (throws std::invalid_argument naming the key).
  LinkModel(const LinkProfile& profile, std::uint64_t seed, std::uint64_t stream);

  /// Decides what happens to a datagram of `bytes` offered at now_ns. Offers must come in
  /// non-decreasing time.
  Fate offer(std::size_t bytes, std::int64_t now_ns);
  /// The one-way delay of a datagram: base plus a jitter sample (ms, >= 0).
  double sampleDelayMs();
  /// Whether the Gilbert–Elliott chain loses the next datagram (then steps the chain).
  bool lose();

  const LinkProfile& profile() const { return profile_; }
  const LinkCounters& counters() const { return counters_; }
  bool inBadState() const { return bad_; }

 private:
  double normal();

  LinkProfile profile_;
  Pcg32 rng_;
  bool bad_ = false;
  std::int64_t busy_until_ns_ = 0;  // when the cap has sent everything queued so far
  std::int64_t last_due_ns_ = 0;    // the FIFO floor of in-order datagrams
  double pareto_scale_ms_ = 0;      // Lomax scale: mean (alpha - 1)
  LinkCounters counters_;
};

}  // namespace zonesim::gateway
