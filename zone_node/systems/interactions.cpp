#include "zone_node/systems/interactions.h"

#include <algorithm>
#include <cmath>

#include "common/splitmix.h"
#include "zone_node/systems/nearest_grid.h"
#include "zone_node/tick_profile.h"

namespace zonesim::zone {

namespace {

std::uint64_t everyTicks(double seconds, double dt) {
  return std::max<std::uint64_t>(1, std::uint64_t(std::llround(seconds / dt)));
}

bool canBeHit(EntityKind k) {
  return k == EntityKind::Npc || k == EntityKind::Avatar;
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
  const bool hits = settings_.hit_reach > 0 && settings_.hit_damage > 0;
  const bool gifts = settings_.gift_reach > 0;
  NearestGrid<Candidate> grid(std::max({settings_.hit_reach, settings_.gift_reach, 1e-3}));
  for (std::size_t i = 0; i < store.size(); ++i)
    if (canBeHit(store.kind[i]))
      grid.add({store.id[i], store.kind[i], store.pos[i].x(), store.pos[i].z(), rank_});
  if (ctx.ghosts)
    for (std::size_t g = 0; g < ctx.ghosts->size(); ++g)
      if (canBeHit(ctx.ghosts->kind[g]))
        grid.add({ctx.ghosts->id[g], ctx.ghosts->kind[g], ctx.ghosts->pos[g].x(),
                  ctx.ghosts->pos[g].z(), ctx.ghosts->owner[g]});
  for (std::size_t i = 0; i < store.size(); ++i) {
    const double x = store.pos[i].x(), z = store.pos[i].z();
    const EntityId self = store.id[i];
    auto anyone = [self](const Candidate& c) { return c.id != self; };
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
  }
}

void InteractionSystem::receive(EntityStore& store, std::span<const EntityMessage> arrived,
                                std::vector<EntityMessage>& replies,
                                TickCounters& counters) const {
  for (const EntityMessage& m : arrived) {
    const std::size_t i = *store.indexOf(m.to);  // the mail delivers only to entities here
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
        EntityMessage r;
        r.from = m.to;
        r.to = m.from;
        r.seq = ++c.mail_seq;
        r.kind = MailKind::KillConfirmed;
        r.to_rank = m.reply_rank;
        replies.push_back(r);
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
      case MailKind::Count:
        break;
    }
  }
}

void InteractionSystem::refused(const EntityMessage& m, std::vector<EntityMessage>& replies,
                                TickCounters&) const {
  if (m.kind != MailKind::Gift) return;
  // The recipient is gone and posts nothing: the return is the gift's own, numbered as it was
  // (its kind keeps its audit key apart from the gift's).
  EntityMessage r = m;
  r.to = m.from;
  r.kind = MailKind::GiftReturned;
  r.forwarded = 0;
  r.to_rank = m.reply_rank;
  replies.push_back(r);
}

}  // namespace zonesim::zone
