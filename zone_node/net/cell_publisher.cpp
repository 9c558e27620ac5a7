#include "zone_node/net/cell_publisher.h"

#include <algorithm>

#include "common/scene.h"
#include "idl/dds_qos.h"
#include "idl/dr_sample.h"
#include "zone_node/net/dead_reckoning.h"

namespace zonesim::zone {

namespace {

using dds_Vec3f = zonesim_dds_Vec3f;

dds_Vec3f toVec3f(const dr::V3& v) {
  return {float(v.x), float(v.y), float(v.z)};
}

/// The wire sample of a quantised state: what every receiver decodes.
zonesim_dds_EntityUpdate toSample(EntityId id, EntityKind kind, const dr::Model& m,
                                  const dr::State& s, int rot_largest) {
  zonesim_dds_EntityUpdate u{};
  u.id = id.value;
  u.kind = std::uint8_t(kind);
  u.pos = toVec3f(s.pos);
  u.vel = toVec3f(s.vel);
  u.rot = {float(s.rot.x), float(s.rot.y), float(s.rot.z), float(s.rot.w)};
  u.acc = toVec3f(s.acc);
  u.angvel = toVec3f(s.angvel);
  u.model = dds::packModel(m, rot_largest);
  return u;
}

template <typename Seq, typename T>
void view(Seq& seq, std::vector<T>& v) {
  seq._maximum = seq._length = std::uint32_t(v.size());
  seq._buffer = v.data();
  seq._release = false;  // the vector owns the memory
}

/// A listener that keeps a writer's matched readers, now and ever (a reader replacing another
/// between two ticks leaves the first unchanged but not the second), in `counts`.
template <typename Counts>
void onPublicationMatched(dds_entity_t, const dds_publication_matched_status_t status, void* arg) {
  auto* counts = static_cast<Counts*>(arg);
  const std::uint32_t before =
      counts->now.exchange(status.current_count, std::memory_order_relaxed);
  counts->ever.store(status.total_count, std::memory_order_relaxed);
  counts->all_now->fetch_add(std::int64_t(status.current_count) - std::int64_t(before),
                             std::memory_order_relaxed);
}

}  // namespace

CellPublisher::CellPublisher(dds_entity_t participant, const dds::Topics& topics,
                             const InterestGrid& grid, int zone, const Scene& scene,
                             std::uint32_t epoch)
    : participant_(participant),
      update_topic_(topics.cell_updates.get()),
      keyframe_topic_(topics.cell_keyframes.get()),
      grid_(grid),
      zone_(zone),
      reckoner_(scene.dead_reckoning, dr::codecParams(scene)),
      keyframe_every_(scene.keyframe_every),
      epoch_(epoch) {}

CellPublisher::Channel& CellPublisher::channel(int cell) {
  auto it = channels_.find(cell);
  if (it != channels_.end()) return it->second;
  std::string partition = dds::cellPartition(grid_.columnOfCell(cell), grid_.rowOfCell(cell));
  Channel ch;
  ch.updates_matched = std::make_unique<MatchCounts>();
  ch.keyframes_matched = std::make_unique<MatchCounts>();
  ch.updates_matched->all_now = ch.keyframes_matched->all_now = &readers_now_;
  // The listener is copied into the writer: ours is deleted once the writer exists.
  auto writerCounting = [&](dds_entity_t topic, const dds::Qos& qos, MatchCounts* counts) {
    std::unique_ptr<dds_listener_t, void (*)(dds_listener_t*)> listener(dds_create_listener(counts),
                                                                        dds_delete_listener);
    dds_lset_publication_matched(listener.get(), onPublicationMatched<MatchCounts>);
    return dds::makePartitionWriter(participant_, topic, partition, qos.get(), listener.get());
  };
  dds::Qos uq = dds::cellUpdateQos(), kq = dds::cellKeyframeQos();
  ch.updates = writerCounting(update_topic_, uq, ch.updates_matched.get());
  ch.keyframes = writerCounting(keyframe_topic_, kq, ch.keyframes_matched.get());
  return channels_.emplace(cell, std::move(ch)).first->second;
}

void CellPublisher::cover(double min_x, double min_z, double max_x, double max_z) {
  for (int iz = grid_.rowOf(min_z); iz <= grid_.rowOf(max_z); ++iz)
    for (int ix = grid_.columnOf(min_x); ix <= grid_.columnOf(max_x); ++ix)
      channel(iz * grid_.columns() + ix);
}

void CellPublisher::refreshSubscriptions(std::uint64_t tick, PublishStats& stats) {
  // No reader anywhere, and every cell already marked so: nothing to refresh. (A reader that
  // matches meanwhile is seen at the next tick, as any discovery is.)
  if (!any_subscribed_ && readers_now_.load(std::memory_order_relaxed) == 0) return;
  bool periodic = keyframe_every_ > 0 && tick % std::uint64_t(keyframe_every_) == 0;
  bool readers_moved = false;
  for (auto& [cell, ch] : channels_) {
    const MatchCounts& u = *ch.updates_matched;
    const MatchCounts& k = *ch.keyframes_matched;
    std::uint32_t matched =
                      u.now.load(std::memory_order_relaxed) + k.now.load(std::memory_order_relaxed),
                  ever = u.ever.load(std::memory_order_relaxed) +
                         k.ever.load(std::memory_order_relaxed);
    // A new reader gets a fresh keyframe, so it starts from the current state.
    ch.keyframe_due = matched > 0 && (ever > ch.matched_ever || periodic);
    ch.all_readers_new = matched > 0 && ch.matched == 0;
    readers_moved |= ch.subscribed != (matched > 0);
    ch.subscribed = matched > 0;
    ch.matched = matched;
    ch.matched_ever = ever;
    stats.subscribed_cells += ch.subscribed;
  }
  any_subscribed_ = stats.subscribed_cells > 0;
  if (readers_moved || near_reader_.empty()) markCellsNearReaders();
}

void CellPublisher::markCellsNearReaders() {
  near_reader_.assign(std::size_t(grid_.cellCount()), 0);
  const int columns = grid_.columns(), rows = grid_.rows();
  for (const auto& [cell, ch] : channels_) {
    if (!ch.subscribed) continue;
    const int ix = cell % columns, iz = cell / columns;
    for (int z = std::max(iz - 1, 0); z <= std::min(iz + 1, rows - 1); ++z)
      for (int x = std::max(ix - 1, 0); x <= std::min(ix + 1, columns - 1); ++x)
        near_reader_[std::size_t(z * columns + x)] = 1;
  }
}

PublishStats CellPublisher::publish(EntityStore& store, std::span<const Departure> leavers,
                                    std::uint64_t tick, double sim_time) {
  PublishStats stats;
  refreshSubscriptions(tick, stats);
  double dt = last_sim_time_ >= 0 ? sim_time - last_sim_time_ : 0;
  last_sim_time_ = sim_time;
  if (stats.subscribed_cells == 0) {
    // Nobody reads any cell: no state, no leave and no motion history is needed (the zone's
    // cells have writers already, from cover()). The first reader gets a keyframe.
    idle_ = true;
    return stats;
  }
  if (idle_) {
    // Publishing again after ticks that tracked nothing: every entity starts afresh, as if new
    // (its first state is estimated from its velocity; no leave for a cell it left meanwhile).
    for (std::size_t i = 0; i < store.size(); ++i) {
      DeadReckoningState& d = store.dr[i];
      d.cell = -1;
      d.has_last = false;
      d.vel_count = 0;
      d.vel_next = 0;
    }
    idle_ = false;
  }
  // Each entity's cell and channel, looked up once (map nodes never move). A channel made here
  // for a fresh cell has no reader yet, as the refresh would have found.
  entity_cell_.resize(store.size());
  entity_channel_.resize(store.size());
  for (std::size_t i = 0; i < store.size(); ++i) {
    entity_cell_[i] = grid_.cellOf(store.pos[i].x(), store.pos[i].z());
    entity_channel_[i] = &channel(entity_cell_[i]);
  }
  for (std::size_t i = 0; i < store.size(); ++i) {
    const int cell = entity_cell_[i];
    DeadReckoningState& dr = store.dr[i];
    EntityId id = store.id[i];
    EntityKind kind = store.kind[i];
    Channel& ch = *entity_channel_[i];
    int previous = dr.cell;
    dr.cell = cell;
    if (previous != cell && previous >= 0) {
      Channel& old = channels_.find(previous)->second;
      if (old.subscribed) old.leaves.push_back({id.value, zonesim_dds_LEAVE_MOVED_CELL});
    }
    if (!ch.subscribed) {
      // Not computed, not encoded; a keyframe resynchronises on subscription. Next to a read
      // cell the history the motion estimate needs is kept, so the state a reader first gets
      // when the entity crosses over is right; farther away the entity starts afresh when it
      // comes near (its first state estimated from its velocity, as after an idle zone).
      if (near_reader_[std::size_t(cell)]) {
        rememberTick(store, i);
        ++stats.histories_kept;
      } else {
        dr.has_last = false;
        dr.vel_count = 0;
        dr.vel_next = 0;
      }
      continue;
    }
    dr::State truth = trueState(store, i, dt);  // from last tick's history, then remember
    rememberTick(store, i);
    ++stats.states_computed;
    ++stats.histories_kept;
    dr::Model model = modelFor(reckoner_.config(), kind);
    auto sendNow = [&](std::vector<zonesim_dds_EntityUpdate>& out) {
      int largest = -1;
      dr::State q = reckoner_.quantised(truth, kind, cell, &largest);
      out.push_back(toSample(id, kind, model, q, largest));
      DeadReckoner::markSent(dr, q, sim_time);
    };
    if (ch.keyframe_due) {
      // Readers that start with this keyframe know exactly this state. Readers already
      // following the cell keep to the dead-reckoning stream: for them a periodic keyframe is
      // no reason to resend anything.
      if (ch.all_readers_new) {
        sendNow(ch.keyframe);
        continue;
      }
      int largest = -1;
      dr::State q = reckoner_.quantised(truth, kind, cell, &largest);
      ch.keyframe.push_back(toSample(id, kind, model, q, largest));
    }
    if (previous != cell) {
      sendNow(ch.enters);
      continue;
    }
    switch (reckoner_.due(dr, id, kind, truth, sim_time)) {
      case dr::Due::None:
        ++stats.suppressed;
        continue;
      case dr::Due::Position:
        ++stats.position_updates;
        break;
      case dr::Due::Orientation:
        ++stats.orientation_updates;
        break;
      case dr::Due::Heartbeat:
        ++stats.heartbeats;
        break;
      case dr::Due::Rest:
        ++stats.rest_updates;
        break;
    }
    sendNow(ch.updates_out);
  }
  for (const Departure& d : leavers) {
    if (d.last_cell < 0) continue;
    auto it = channels_.find(d.last_cell);
    std::uint8_t reason = d.to_rank >= 0 ? zonesim_dds_LEAVE_MIGRATED : zonesim_dds_LEAVE_DESTROYED;
    if (it != channels_.end() && it->second.subscribed)
      it->second.leaves.push_back({d.id.value, reason});
  }
  for (auto& [cell, ch] : channels_) write(cell, ch, tick, sim_time, stats);
  return stats;
}

void CellPublisher::write(int cell, Channel& ch, std::uint64_t tick, double sim_time,
                          PublishStats& stats) {
  if (!ch.enters.empty() || !ch.updates_out.empty() || !ch.leaves.empty()) {
    zonesim_dds_CellUpdateBatch b{};
    b.cell = cell;
    b.zone = zone_;
    b.tick = tick;
    b.sim_time = sim_time;
    b.dilation = dilation_;
    b.epoch = epoch_;
    view(b.enters, ch.enters);
    view(b.updates, ch.updates_out);
    view(b.leaves, ch.leaves);
    // A reader that stopped reading makes a reliable write time out: count it, never stall.
    if (dds_write(ch.updates.writer.get(), &b) < 0) ++stats.write_failures;
    ++stats.cells_written;
    stats.enters += ch.enters.size();
    stats.updates += ch.updates_out.size();
    stats.leaves += ch.leaves.size();
  }
  if (ch.keyframe_due) {
    zonesim_dds_CellKeyframe k{};
    k.cell = cell;
    k.zone = zone_;
    k.tick = tick;
    k.sim_time = sim_time;
    k.dilation = dilation_;
    k.epoch = epoch_;
    view(k.entities, ch.keyframe);
    if (dds_write(ch.keyframes.writer.get(), &k) < 0) ++stats.write_failures;
    ++stats.keyframes;
  }
  ch.enters.clear();
  ch.updates_out.clear();
  ch.leaves.clear();
  ch.keyframe.clear();
}

}  // namespace zonesim::zone
