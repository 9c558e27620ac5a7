#pragma once
// What entities do to each other (the scene's `interactions` key), as messages through the
// entity mail (cluster/entity_mail.h), so a target across a zone border, or migrating in this
// very tick, is reached exactly once:
// - an NPC hits the nearest other NPC or avatar within reach, every hit_every_s: the target
//   loses health and is pushed away; a hit that takes the health to 0 kills, and the victim's
//   owner confirms the kill to the hitter (seed 3.3.3: the killer waits for the victim);
// - an avatar with items hands one to the nearest other avatar within reach, every
//   gift_every_s; a gift whose recipient is gone goes back to its giver, so items are never
//   lost or made;
// - an NPC or avatar within reach of a unique item claims it; the item's owner alone decides:
//   of the claims of one tick (seed 3.3.3's contested event, say two players across a border)
//   the nearest claimant wins, the lowest id on a tie, whatever the decomposition. The winner
//   is told (the item joins its items), the others are denied, and the item is marked taken:
//   the zone removes it once a checkpoint holds the decision (ZoneNode::removeTakenItems), so
//   a client never sees an item go that a restart would bring back.
// Choices are made in the AI phase, first, from positions at the tick's start (the ghosts'
// too); messages are applied in the migrate phase, sorted, so every decomposition agrees.

#include <cstdint>
#include <span>
#include <vector>

#include "common/scene_interactions.h"
#include "zone_node/cluster/entity_mail.h"
#include "zone_node/systems/step_context.h"

namespace zonesim::zone {

struct TickCounters;

class InteractionSystem : public ZoneSystem {
 public:
  /// Posts into `mail` (which the zone delivers in its migrate phase); `rank`: this zone's.
  InteractionSystem(const InteractionSettings& settings, double dt, EntityMail& mail, int rank);

  bool active() const override { return settings_.enabled; }
  /// NPCs due to hit and avatars due to give choose their targets and post.
  void step(StepContext& ctx) override;
  /// Whether items are taken, on ghosts too (a taken item is claimed no more).
  std::vector<GhostColumn> ghostColumns() const override;
  /// Applies a tick's arrivals to this zone's entities (EntityMail's receiver).
  void receive(EntityStore& store, std::span<const EntityMessage> arrived,
               std::vector<EntityMessage>& replies, TickCounters& counters);
  /// A gift whose recipient is gone goes back to its giver, a claim on an item that is gone is
  /// denied (EntityMail's refusal hook).
  void refused(const EntityMessage& m, std::vector<EntityMessage>& replies,
               TickCounters& counters) const;

 private:
  struct Candidate {
    EntityId id;
    EntityKind kind;
    double x, z;
    int rank;
  };
  /// Whether entity `id` acts this tick, once every `every` ticks (phases spread by id).
  static bool due(EntityId id, std::uint64_t tick, std::uint64_t every);
  void post(EntityStore& store, std::size_t sender, const Candidate& target, MailKind kind,
            std::int32_t amount);
  /// Decides the claims on item `item` (one tick's, sorted by claimant): replies to each.
  void decideClaims(EntityStore& store, std::size_t item, std::span<const EntityMessage> claims,
                    std::vector<EntityMessage>& replies, TickCounters& counters);

  InteractionSettings settings_;
  std::uint64_t hit_every_, gift_every_;  // in ticks
  EntityMail& mail_;
  int rank_;
  std::uint64_t tick_ = 0;  // the tick being stepped (decisions are stamped with it)
};

}  // namespace zonesim::zone
