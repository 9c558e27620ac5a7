#include "zone_node/players.h"

#include <algorithm>
#include <optional>

#include "common/log.h"
#include "common/scene.h"
#include "zone_node/avatar_spawn.h"
#include "zone_node/cluster/migration.h"
#include "zone_node/net/gateway_link.h"
#include "zone_node/tick_profile.h"

namespace zonesim::zone {

Players::Players(const Scene& scene, int rank, int ranks, int orphan_grace_ticks)
    : scene_(scene),
      rank_(rank),
      ranks_(ranks),
      forward_(std::size_t(ranks)),
      orphan_grace_ticks_(std::uint64_t(std::max(0, orphan_grace_ticks))) {}

void Players::restored(PlayerZone& zone) {
  const EntityStore& store = zone.store;
  hold_until_tick_ = zone.tick + kRestoreHoldTicks;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Avatar) continue;
    known_players_.insert(store.avatar[i].player_id);
    last_input_tick_[store.avatar[i].player_id] = zone.tick;
    awaiting_resend_.insert(store.avatar[i].player_id);
    if (zone.link)
      zone.link->announce({store.avatar[i].player_id, store.id[i].value, -1, rank_, zone.tick,
                           store.avatar[i].last_input_seq});
  }
}

void Players::input(PlayerZone& zone) {
  for (const ForwardedInput& f : forwarded_in_)
    applyInput(zone, f.player_id, f.seq, f.move_x, f.move_z);
  forwarded_in_.clear();
  if (zone.link) {
    for (const SpawnRequestMsg& s : zone.link->takeSpawnRequests()) spawnAvatar(zone, s);
    for (const DespawnRequestMsg& d : zone.link->takeDespawnRequests()) despawnAvatar(zone, d);
    for (const PlayerInputMsg& in : zone.link->takeInputs())
      applyInput(zone, in.player_id, in.seq, in.move_x, in.move_z);
  }
  releaseHeldInputs(zone);
  removeOrphans(zone);
  announceAwaiting(zone);
}

void Players::announceAwaiting(PlayerZone& zone) {
  if (awaiting_resend_.empty()) return;
  if (zone.tick >= hold_until_tick_) {
    awaiting_resend_.clear();
    return;
  }
  if (!zone.link || zone.tick % kReannounceTicks != 0) return;
  for (std::uint64_t player : awaiting_resend_)
    if (std::optional<std::size_t> i = zone.store.avatarOf(player))
      zone.link->announce({player, zone.store.id[*i].value, -1, rank_, zone.tick,
                           zone.store.avatar[*i].last_input_seq});
}

void Players::removeOrphans(PlayerZone& zone) {
  if (orphan_grace_ticks_ == 0 || zone.tick % std::uint64_t(std::max(1.0, scene_.tick_rate)) != 0)
    return;
  EntityStore& store = zone.store;
  std::vector<std::uint64_t> orphans;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Avatar) continue;
    std::uint64_t player = store.avatar[i].player_id;
    // An avatar first seen here (arrived, restored) starts its grace now.
    auto [heard, first] = last_input_tick_.try_emplace(player, zone.tick);
    if (!first && zone.tick - heard->second > orphan_grace_ticks_) orphans.push_back(player);
  }
  for (std::uint64_t player : orphans) {
    ZS_INFO("player %llu sent no input for %llu ticks: avatar removed",
            (unsigned long long)player, (unsigned long long)orphan_grace_ticks_);
    last_input_tick_.erase(player);
    held_inputs_.erase(player);
    destroyAt(zone, *store.avatarOf(player));
    ++zone.counters.avatars_orphaned;
  }
}

void Players::spawnAvatar(PlayerZone& zone, const SpawnRequestMsg& request) {
  std::uint64_t player_id = request.player_id;
  EntityStore& store = zone.store;
  // Every zone reads every request, so all agree on which players exist; repeats are ignored,
  // and so is a request whose player already left (the despawn overtook it).
  bool seen = !known_players_.insert(player_id).second;
  if (despawned_players_.count(player_id)) return;
  session_of_[player_id] = request.session;
  std::optional<std::size_t> mine = store.avatarOf(player_id);
  if (seen) {
    if (mine && zone.link) {
      zone.link->announce({player_id, store.id[*mine].value, -1, rank_, zone.tick,
                           store.avatar[*mine].last_input_seq});
    }
    return;
  }
  // The creator is chosen without the layout: zones read the request in different ticks, and
  // boundaries may move in between. Migration then takes the avatar to its owner, which
  // announces it (see migrated()).
  if (player_id % std::uint64_t(ranks_) != std::uint64_t(rank_)) return;
  std::optional<EntityRecordData> made =
      newAvatar(scene_, player_id, request.x, request.z, request.kind);
  if (!made) {
    // Its gateway reads another scene: no avatar of a kind this world has no speed for. The
    // player's session times out, pending, at the gateway.
    ++zone.counters.avatars_refused;
    ZS_WARN("player %llu asked for an avatar of kind %u, which the scene does not list",
            (unsigned long long)player_id, unsigned(request.kind));
    return;
  }
  EntityRecordData& r = *made;
  r.id = zone.ids.next();
  store.add(r);
  zone.ledger.add(r.id);
  last_input_tick_[player_id] = zone.tick;
  ++zone.counters.avatars_spawned;
  unannounced_.push_back(r.id);
  ZS_DEBUG("spawned avatar %s for player %llu", toString(r.id).c_str(),
           (unsigned long long)player_id);
}

void Players::despawnAvatar(PlayerZone& zone, const DespawnRequestMsg& request) {
  std::uint64_t player_id = request.player_id;
  // A session the player left by resuming at another gateway (which asked for the avatar
  // since) times out there; the player plays on. Requests of one player are seconds apart, so
  // every zone reads the two in the same order.
  if (auto newest = session_of_.find(player_id);
      newest != session_of_.end() && newest->second != request.session) {
    if (zone.store.avatarOf(player_id)) ++zone.counters.despawns_superseded;  // once, by its owner
    return;
  }
  session_of_.erase(player_id);
  // Every zone remembers the request: an avatar migrating while zones read it is removed on
  // arrival at a zone that has already seen it.
  despawned_players_.insert(player_id);
  departed_players_.erase(player_id);
  last_input_tick_.erase(player_id);
  if (std::optional<std::size_t> i = zone.store.avatarOf(player_id)) destroyAt(zone, *i);
}

void Players::destroyAt(PlayerZone& zone, std::size_t index) {
  EntityStore& store = zone.store;
  zone.leavers.push_back({store.id[index], store.kind[index], -1, store.dr[index].cell,
                          store.avatar[index].player_id, false});
  zone.ledger.remove(store.id[index]);
  store.removeAt(index);
  ++zone.counters.entities_destroyed;
}

void Players::applyInput(PlayerZone& zone, std::uint64_t player_id, std::uint32_t seq, float move_x,
                         float move_z) {
  if (std::optional<std::size_t> i = zone.store.avatarOf(player_id)) {
    AvatarData& a = zone.store.avatar[*i];
    last_input_tick_[player_id] = zone.tick;
    if (seq <= a.last_input_seq) {
      ++zone.counters.inputs_duplicate;  // already applied (e.g. forwarded copy): exactly once
      return;
    }
    // Ahead of a missing number (typically the forwarded input the old owner still holds after
    // a handoff): held until the gap fills or kInputHoldTicks pass, so inputs apply in order.
    if (a.last_input_seq != 0 && seq > a.last_input_seq + 1) {
      if (held_inputs_[player_id].try_emplace(seq, HeldInput{move_x, move_z, zone.tick}).second)
        ++zone.counters.inputs_held;
      return;
    }
    a.last_input_seq = seq;
    awaiting_resend_.erase(player_id);
    a.move_x = move_x;
    a.move_z = move_z;
    ++zone.counters.inputs_applied;
    auto started = handoff_started_.find(player_id);
    if (started != handoff_started_.end()) {
      handoffs_completed_.push_back({player_id, zone.tick - started->second});
      handoff_started_.erase(started);
    }
    return;
  }
  auto gone = departed_players_.find(player_id);
  if (gone != departed_players_.end()) {
    forward_[std::size_t(gone->second)].push_back({player_id, seq, move_x, move_z});
    ++zone.counters.inputs_forwarded;
    return;
  }
  ++zone.counters.inputs_unroutable;
}

void Players::releaseHeldInputs(PlayerZone& zone) {
  for (auto player = held_inputs_.begin(); player != held_inputs_.end();) {
    std::map<std::uint32_t, HeldInput>& held = player->second;
    std::optional<std::size_t> i = zone.store.avatarOf(player->first);
    while (!held.empty()) {
      auto [seq, in] = *held.begin();
      if (i) {
        AvatarData& a = zone.store.avatar[*i];
        if (seq > a.last_input_seq + 1) {
          // The gap may still fill: soon, or, after a restart, once the gateway resends.
          bool resend_due = zone.tick < hold_until_tick_ && awaiting_resend_.count(player->first);
          if (zone.tick - in.since_tick < kInputHoldTicks || resend_due) break;
          zone.counters.inputs_skipped += seq - a.last_input_seq - 1;  // it did not: never arrived
          ZS_DEBUG("player %llu: inputs %u..%u never arrived, skipped", (unsigned long long)player->first,
                  a.last_input_seq + 1, seq - 1);
          a.last_input_seq = seq - 1;
        }
      }
      held.erase(held.begin());
      applyInput(zone, player->first, seq, in.move_x, in.move_z);  // here, or forwarded if it left
    }
    player = held.empty() ? held_inputs_.erase(player) : std::next(player);
  }
}

void Players::migrated(PlayerZone& zone, MigrationResult& result) {
  EntityStore& store = zone.store;
  for (const Departure& d : result.departed) {
    if (!d.announced_avatar) continue;
    departed_players_[d.player_id] = d.to_rank;
    last_input_tick_.erase(d.player_id);
    ++zone.counters.handoffs_out;
  }
  std::vector<EntityId> gone_players;
  for (const Arrival& a : result.arrived) {
    if (store.kind[a.index] != EntityKind::Avatar) continue;
    const AvatarData& av = store.avatar[a.index];
    departed_players_.erase(av.player_id);
    last_input_tick_[av.player_id] = zone.tick;
    if (despawned_players_.count(av.player_id)) {
      gone_players.push_back(store.id[a.index]);
      continue;
    }
    if (!av.announced) {
      unannounced_.push_back(store.id[a.index]);  // a new avatar on its way from its creator
      continue;
    }
    ++zone.counters.handoffs_in;
    handoff_started_[av.player_id] = zone.tick;
    if (zone.link)
      zone.link->announce({av.player_id, store.id[a.index].value, a.from_rank, rank_, zone.tick,
                           av.last_input_seq});
  }
  // Removed after the loop: removal moves entities and would invalidate the arrival indices.
  for (EntityId id : gone_players) destroyAt(zone, *store.indexOf(id));
  // New avatars that ended this exchange here are this zone's to announce as created.
  for (EntityId id : unannounced_) {
    std::optional<std::size_t> i = store.indexOf(id);
    if (!i) continue;  // migrated on: the owner announces it
    AvatarData& av = store.avatar[*i];
    av.announced = true;
    if (zone.link)
      zone.link->announce({av.player_id, id.value, -1, rank_, zone.tick, av.last_input_seq});
  }
  unannounced_.clear();
  forwarded_in_ = std::move(result.inputs);
}

}  // namespace zonesim::zone
