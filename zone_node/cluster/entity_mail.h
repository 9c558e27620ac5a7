#pragma once
// Messages between entities, across zones (an NPC hits a player, a player hands another an
// item): the class of message KBEngine loses when its target is migrating (issue #978). Here
// every message posted in a tick is applied, or refused with a reason, in that same tick's
// migrate phase, after the entities' exchange:
//   round 1: each goes to the rank the sender saw its target on (its own, or the ghost's
//            owner: the owner at the tick's start). There the target is found, or it left in
//            this tick's exchange, at most once, and the message follows it (forwarded);
//   round 2: forwarded messages reach the target's new owner; replies made in round 1 (a kill
//            confirmed, a gift returned) go to their sender's owner after the exchange, exact;
//   round 3: replies made in round 2.
// A reply makes no reply, so nothing is in flight between ticks: a checkpoint is a consistent
// cut, and a zone restored from one owes no message. Arrivals are applied sorted by (target,
// sender, number), never in arrival order, so the result does not depend on how many ranks
// there are. The audit (posted = applied + refused, as counts and order-independent hashes of
// (sender, number)) is summed over the cluster with the conservation check.

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <type_traits>
#include <vector>

#include "common/entity_id.h"
#include "zone_node/cluster/byte_exchange.h"
#include "zone_node/departure.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// What a message asks of its target.
enum class MailKind : std::uint8_t {
  Hit = 0,            ///< lose `amount` health (a kill is confirmed back)
  Gift = 1,           ///< take `amount` items from the sender
  KillConfirmed = 2,  ///< reply: the target of your hit died of it
  GiftReturned = 3,   ///< reply: your gift could not be delivered; take the items back
  Pickup = 4,         ///< to an item: the sender takes it (its owner decides a contest)
  PickupGranted = 5,  ///< reply: the item is yours
  PickupDenied = 6,   ///< reply: someone nearer took it, or it was gone
  Count = 7
};
/// Names as counters and logs write them, in MailKind order.
inline constexpr std::string_view kMailKindNames[] = {
    "hit", "gift", "kill_confirmed", "gift_returned", "pickup", "pickup_granted", "pickup_denied"};
/// Whether a kind is a reply (which never makes one).
constexpr bool isReply(MailKind k) {
  return k == MailKind::KillConfirmed || k == MailKind::GiftReturned ||
         k == MailKind::PickupGranted || k == MailKind::PickupDenied;
}

/// One message. Raw, fixed-size and trivially copyable (ranks of one job share the layout; the
/// size and every field are checked on arrival): a tick moves thousands.
struct EntityMessage {
  EntityId from, to;
  std::uint32_t seq = 0;  ///< the sender's number (CombatData::mail_seq): (from, seq) is unique
  MailKind kind = MailKind::Hit;
  std::uint8_t forwarded = 0;  ///< 1 once it followed its migrating target
  std::uint16_t reserved = 0;
  std::int32_t amount = 0;
  std::int32_t to_rank = -1;     ///< where it is sent this round
  std::int32_t reply_rank = -1;  ///< the sender's owner after this tick's exchange
  std::int32_t from_rank = -1;   ///< the rank it was posted on
  double from_x = 0, from_z = 0;  ///< the sender's position when posted
};
static_assert(std::is_trivially_copyable_v<EntityMessage> && sizeof(EntityMessage) == 56,
              "EntityMessage travels as raw bytes between ranks");

/// Why a message was not applied.
enum class MailRefusal : std::uint8_t { TargetGone = 0, Count = 1 };

/// Counts and hashes that must balance over the cluster: every message posted is applied or
/// refused, once.
struct MailAudit {
  IdSetDigest posted, applied, refused;
};

/// The cluster's audit, summed: every message posted was applied or refused, once.
struct MailBalance {
  IdSetDigest posted;
  IdSetDigest settled;  ///< applied plus refused
  bool ok() const { return posted == settled; }
};
/// Collective: sums every rank's audit (one allreduce).
MailBalance sumMailAudit(MPI_Comm comm, const MailAudit& audit);

/// What one tick's delivery did on this rank.
struct MailStats {
  std::uint64_t posted = 0;      ///< messages and replies posted here
  std::uint64_t applied = 0;     ///< applied to this rank's entities
  std::uint64_t cross_zone = 0;  ///< of those, posted on another rank
  std::uint64_t forwarded = 0;   ///< passed on after their target left this rank
  std::uint64_t refused = 0;     ///< target gone (destroyed, despawned)
  std::uint64_t bytes_sent = 0;
};

/// Applies arrivals (sorted by target, sender, number) to this rank's entities; a reply goes to
/// `replies` (its to_rank set to the original's reply_rank).
using MailReceiver = std::function<void(EntityStore&, std::span<const EntityMessage> arrived,
                                        std::vector<EntityMessage>& replies)>;
/// Called for each refused message (so a gift's items go back to its sender).
using MailRefused = std::function<void(const EntityMessage&, MailRefusal,
                                       std::vector<EntityMessage>& replies)>;

class EntityMail {
 public:
  EntityMail(MPI_Comm comm, int rank, int size);

  /// Posts a message from a local entity during the tick; `m.to_rank` is where the sender saw
  /// its target (this rank or the ghost's owner).
  void post(const EntityMessage& m);
  /// Migrate phase, after the exchange (collective on every rank, every tick the scene has
  /// interactions): delivers everything posted this tick. `departed`: this tick's leavers.
  MailStats deliver(EntityStore& store, const std::vector<Departure>& departed,
                    const MailReceiver& receive, const MailRefused& refused);
  /// Since the zone started (or was restored): nothing posted is ever in flight at a tick's end.
  const MailAudit& audit() const { return audit_; }

  /// The key a message is audited under.
  static EntityId auditKey(const EntityMessage& m);

 private:
  /// Sends `out` by to_rank and returns what reached this rank, sorted (collective).
  std::vector<EntityMessage> exchange(std::vector<EntityMessage>& out, MailStats& stats);

  int rank_, size_;
  ByteExchange bytes_;
  std::vector<EntityMessage> posted_;
  MailAudit audit_;
};

}  // namespace zonesim::zone
