#include "zone_node/cluster/entity_mail.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "common/splitmix.h"

namespace zonesim::zone {

namespace {

// Round 1 reaches the owner at the tick's start, round 2 the owner after the exchange (and the
// replies of round 1), round 3 the replies of round 2: replies make none.
constexpr int kRounds = 3;

bool sortedBefore(const EntityMessage& a, const EntityMessage& b) {
  if (a.to.value != b.to.value) return a.to.value < b.to.value;
  if (a.from.value != b.from.value) return a.from.value < b.from.value;
  return a.seq < b.seq;
}

void checkArrival(const EntityMessage& m, int size) {
  if (std::uint8_t(m.kind) >= std::uint8_t(MailKind::Count))
    throw std::runtime_error("entity mail: a message of unknown kind " +
                             std::to_string(int(m.kind)));
  if (m.reply_rank < 0 || m.reply_rank >= size || m.from_rank < 0 || m.from_rank >= size)
    throw std::runtime_error("entity mail: a message naming a rank outside 0.." +
                             std::to_string(size - 1));
}

}  // namespace

MailBalance sumMailAudit(MPI_Comm comm, const MailAudit& audit) {
  IdSetDigest settled = audit.applied;
  settled.merge(audit.refused);
  // Unsigned sums wrap alike on every rank: the hashes stay order-independent.
  std::uint64_t in[4] = {audit.posted.count, audit.posted.hash, settled.count, settled.hash};
  std::uint64_t out[4] = {};
  MPI_Allreduce(in, out, 4, MPI_UINT64_T, MPI_SUM, comm);
  return {{out[0], out[1]}, {out[2], out[3]}};
}

EntityMail::EntityMail(MPI_Comm comm, int rank, int size)
    : rank_(rank), size_(size), bytes_(comm, size) {}

EntityId EntityMail::auditKey(const EntityMessage& m) {
  return EntityId{splitmix64(m.from.value) ^ (std::uint64_t(m.seq) * 0x9E3779B97F4A7C15ull) ^
                  (std::uint64_t(m.kind) << 56)};
}

void EntityMail::post(const EntityMessage& m) {
  posted_.push_back(m);
  posted_.back().from_rank = rank_;
  audit_.posted.add(auditKey(m));
}

std::vector<EntityMessage> EntityMail::exchange(std::vector<EntityMessage>& out,
                                                MailStats& stats) {
  std::vector<EntityMessage> here;
  if (size_ == 1) {
    here.swap(out);
  } else {
    bytes_.begin();
    for (const EntityMessage& m : out) {
      if (m.to_rank == rank_) {
        here.push_back(m);
        continue;
      }
      std::vector<std::uint8_t>& b = bytes_.outgoing(m.to_rank);
      const auto* raw = reinterpret_cast<const std::uint8_t*>(&m);
      b.insert(b.end(), raw, raw + sizeof m);
    }
    out.clear();
    bytes_.exchange();
    stats.bytes_sent += bytes_.bytesSent();
    for (int r = 0; r < size_; ++r) {
      std::span<const std::uint8_t> in = bytes_.received(r);
      if (in.size() % sizeof(EntityMessage) != 0)
        throw std::runtime_error("entity mail: rank " + std::to_string(r) + " sent " +
                                 std::to_string(in.size()) + " bytes, not whole messages");
      for (std::size_t at = 0; at < in.size(); at += sizeof(EntityMessage)) {
        EntityMessage m;
        std::memcpy(&m, in.data() + at, sizeof m);
        checkArrival(m, size_);
        here.push_back(m);
      }
    }
  }
  std::sort(here.begin(), here.end(), sortedBefore);
  return here;
}

MailStats EntityMail::deliver(EntityStore& store, const std::vector<Departure>& departed,
                              const MailReceiver& receive, const MailRefused& refused) {
  MailStats stats;
  stats.posted = posted_.size();
  std::unordered_map<std::uint64_t, int> went_to;  // looked up only
  for (const Departure& d : departed)
    if (d.to_rank >= 0) went_to[d.id.value] = d.to_rank;
  // A sender that left in this exchange hears its replies at its new owner.
  for (EntityMessage& m : posted_) {
    auto it = went_to.find(m.from.value);
    m.reply_rank = it == went_to.end() ? rank_ : it->second;
  }
  std::vector<EntityMessage> out;
  out.swap(posted_);
  std::vector<EntityMessage> arrived, next;
  for (int round = 0; round < kRounds; ++round) {
    std::vector<EntityMessage> here = exchange(out, stats);
    arrived.clear();
    next.clear();
    std::vector<EntityMessage> replies;
    for (EntityMessage& m : here) {
      if (store.indexOf(m.to)) {
        arrived.push_back(m);
        continue;
      }
      auto it = went_to.find(m.to.value);
      if (it != went_to.end() && !m.forwarded) {
        m.forwarded = 1;
        m.to_rank = it->second;
        next.push_back(m);
        ++stats.forwarded;
        continue;
      }
      ++stats.refused;
      audit_.refused.add(auditKey(m));
      if (refused) refused(m, MailRefusal::TargetGone, replies);
    }
    stats.applied += arrived.size();
    for (const EntityMessage& m : arrived) {
      audit_.applied.add(auditKey(m));
      if (m.from_rank != rank_) ++stats.cross_zone;
    }
    receive(store, arrived, replies);
    // Replies are posted here, this round, and reach their sender's owner next round.
    for (EntityMessage& r : replies) {
      r.from_rank = rank_;
      r.reply_rank = rank_;
      audit_.posted.add(auditKey(r));
      ++stats.posted;
      next.push_back(r);
    }
    out.swap(next);
  }
  // Every rank ran the same rounds; a message left now would be a reply to a reply.
  if (!out.empty())
    throw std::logic_error("entity mail: " + std::to_string(out.size()) +
                           " messages left after the last round (a reply made a reply)");
  return stats;
}

}  // namespace zonesim::zone
