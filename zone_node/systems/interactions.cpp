#include "zone_node/systems/interactions.h"

#include <algorithm>
#include <cmath>

#include "common/splitmix.h"
#include "zone_node/systems/nearest_grid.h"
#include "zone_node/tick_profile.h"

namespace zonesim::zone {

namespace {

constexpr const char* kItemTaken = "item.taken";

std::uint64_t everyTicks(double seconds, double dt) {
  return std::max<std::uint64_t>(1, std::uint64_t(std::llround(seconds / dt)));
}

// NPCs and avatars hit, are hit and claim items; items are claimed.
bool acts(EntityKind k) {
  return k == EntityKind::Npc || k == EntityKind::Avatar;
}
bool inGrid(EntityKind k) {
  return acts(k) || k == EntityKind::Item;
}

/// A reply from entity `from` (numbered by its own mail_seq) to `to` at `to_rank`.
EntityMessage reply(EntityId from, CombatData& from_state, EntityId to, MailKind kind,
                    std::int32_t to_rank) {
  EntityMessage r;
  r.from = from;
  r.to = to;
  r.seq = ++from_state.mail_seq;
  r.kind = kind;
  r.to_rank = to_rank;
  return r;
}

}  // namespace

InteractionSystem::InteractionSystem(const InteractionSettings& settings, double dt,
                                     EntityMail& mail, int rank)
    : settings_(settings),
      hit_every_(everyTicks(settings.hit_every_s, dt)),
      gift_every_(everyTicks(settings.gift_every_s, dt)),
      mail_(mail),
      rank_(rank) {}

bool InteractionSystem::due(EntityId id, std::uint64_t tick, std::uint64_t every) {
  return (tick + splitmix64(id.value) % every) % every == 0;
}

void InteractionSystem::post(EntityStore& store, std::size_t sender, const Candidate& target,
                             MailKind kind, std::int32_t amount) {
  EntityMessage m;
  m.from = store.id[sender];
  m.to = target.id;
  m.seq = ++store.combat[sender].mail_seq;
  m.kind = kind;
  m.amount = amount;
  m.to_rank = target.rank;
  m.from_x = store.pos[sender].x();
  m.from_z = store.pos[sender].z();
  mail_.post(m);
}

void InteractionSystem::step(StepContext& ctx) {
  EntityStore& store = ctx.store;
  tick_ = ctx.tick;
  const bool hits = settings_.hit_reach > 0 && settings_.hit_damage > 0;
  const bool gifts = settings_.gift_reach > 0;
  const bool pickups = settings_.pickup_reach > 0;
  NearestGrid<Candidate> grid(
      std::max({settings_.hit_reach, settings_.gift_reach, settings_.pickup_reach, 1e-3}));
  for (std::size_t i = 0; i < store.size(); ++i)
    if (inGrid(store.kind[i]) && store.combat[i].taken_at == 0)
      grid.add({store.id[i], store.kind[i], store.pos[i].x(), store.pos[i].z(), rank_});
  const std::optional<std::size_t> taken =
      ctx.ghosts ? ctx.ghosts->columnIndex(kItemTaken) : std::nullopt;
  if (ctx.ghosts)
    for (std::size_t g = 0; g < ctx.ghosts->size(); ++g)
      if (inGrid(ctx.ghosts->kind[g]) && !(taken && ctx.ghosts->value(*taken, g) != 0))
        grid.add({ctx.ghosts->id[g], ctx.ghosts->kind[g], ctx.ghosts->pos[g].x(),
                  ctx.ghosts->pos[g].z(), ctx.ghosts->owner[g]});
  for (std::size_t i = 0; i < store.size(); ++i) {
    const double x = store.pos[i].x(), z = store.pos[i].z();
    const EntityId self = store.id[i];
    if (!acts(store.kind[i])) continue;
    auto anyone = [self](const Candidate& c) { return c.id != self && acts(c.kind); };
    auto items = [](const Candidate& c) { return c.kind == EntityKind::Item; };
    auto avatars = [self](const Candidate& c) {
      return c.id != self && c.kind == EntityKind::Avatar;
    };
    double d = 0;
    if (hits && store.kind[i] == EntityKind::Npc && due(store.id[i], ctx.tick, hit_every_)) {
      if (const Candidate* t = grid.nearest(x, z, settings_.hit_reach, anyone, d))
        post(store, i, *t, MailKind::Hit, settings_.hit_damage);
    }
    if (gifts && store.kind[i] == EntityKind::Avatar && store.combat[i].items > 0 &&
        due(store.id[i], ctx.tick, gift_every_)) {
      if (const Candidate* t = grid.nearest(x, z, settings_.gift_reach, avatars, d)) {
        --store.combat[i].items;  // in the gift's hands until it is received or returned
        post(store, i, *t, MailKind::Gift, 1);
      }
    }
    if (pickups)
      if (const Candidate* t = grid.nearest(x, z, settings_.pickup_reach, items, d))
        post(store, i, *t, MailKind::Pickup, 1);
  }
}

std::vector<GhostColumn> InteractionSystem::ghostColumns() const {
  return {{kItemTaken, [](const EntityStore& s, std::vector<std::int64_t>& out) {
             out.resize(s.size());
             for (std::size_t i = 0; i < s.size(); ++i) out[i] = s.combat[i].taken_at != 0;
           }}};
}

void InteractionSystem::decideClaims(EntityStore& store, std::size_t item,
                                     std::span<const EntityMessage> claims,
                                     std::vector<EntityMessage>& replies, TickCounters& counters) {
  const EntityId id = store.id[item];
  CombatData& state = store.combat[item];
  const bool gone = state.taken_at != 0;
  // The nearest claimant where it stood when it claimed; claims come sorted by claimant, so
  // the first of equals (the lowest id) keeps a tie.
  const EntityMessage* winner = nullptr;
  double best = 0;
  if (!gone)
    for (const EntityMessage& c : claims) {
      const double d = std::hypot(c.from_x - store.pos[item].x(), c.from_z - store.pos[item].z());
      if (!winner || d < best) {
        winner = &c;
        best = d;
      }
    }
  for (const EntityMessage& c : claims) {
    const bool won = &c == winner;
    replies.push_back(reply(id, state, c.from,
                            won ? MailKind::PickupGranted : MailKind::PickupDenied, c.reply_rank));
    if (!won) ++counters.pickups_denied;
  }
  if (!winner) return;
  ++counters.pickups;
  if (claims.size() > 1) ++counters.pickups_contested;
  state.taken_at = tick_ + 1;
}

void InteractionSystem::receive(EntityStore& store, std::span<const EntityMessage> arrived,
                                std::vector<EntityMessage>& replies, TickCounters& counters) {
  for (std::size_t k = 0; k < arrived.size(); ++k) {
    const EntityMessage& m = arrived[k];
    const std::size_t i = *store.indexOf(m.to);  // the mail delivers only to entities here
    if (m.kind == MailKind::Pickup) {
      // Every claim on this item in this round: they are next to each other (sorted by target).
      std::size_t end = k + 1;
      while (end < arrived.size() && arrived[end].to == m.to &&
             arrived[end].kind == MailKind::Pickup)
        ++end;
      decideClaims(store, i, arrived.subspan(k, end - k), replies, counters);
      k = end - 1;
      continue;
    }
    CombatData& c = store.combat[i];
    switch (m.kind) {
      case MailKind::Hit: {
        ++counters.hits;
        const double dx = store.pos[i].x() - m.from_x, dz = store.pos[i].z() - m.from_z;
        const double d = std::hypot(dx, dz);
        if (d > 1e-9 && settings_.knockback > 0) {
          store.vel[i].x() += settings_.knockback * dx / d;
          store.vel[i].z() += settings_.knockback * dz / d;
        }
        c.health -= m.amount;
        if (c.health > 0) break;
        // Killed: the victim's owner alone decides it, and tells the hitter.
        ++counters.kills;
        ++c.deaths;
        c.health = 100;
        replies.push_back(reply(m.to, c, m.from, MailKind::KillConfirmed, m.reply_rank));
        break;
      }
      case MailKind::Gift:
        ++counters.gifts;
        c.items += m.amount;
        break;
      case MailKind::KillConfirmed:
        ++c.kills;
        break;
      case MailKind::GiftReturned:
        ++counters.gifts_returned;
        c.items += m.amount;
        break;
      case MailKind::PickupGranted:
        ++c.items;
        break;
      case MailKind::PickupDenied:
      case MailKind::Pickup:
        break;
      case MailKind::Count:
        break;
    }
  }
}

void InteractionSystem::refused(const EntityMessage& m, std::vector<EntityMessage>& replies,
                                TickCounters& counters) const {
  if (m.kind == MailKind::Pickup) ++counters.pickups_denied;
  if (m.kind != MailKind::Gift && m.kind != MailKind::Pickup) return;
  // The recipient is gone and posts nothing: the return is the gift's own, numbered as it was
  // (its kind keeps its audit key apart from the gift's).
  EntityMessage r = m;
  r.to = m.from;
  r.kind = m.kind == MailKind::Gift ? MailKind::GiftReturned : MailKind::PickupDenied;
  r.forwarded = 0;
  r.to_rank = m.reply_rank;
  replies.push_back(r);
}

}  // namespace zonesim::zone
