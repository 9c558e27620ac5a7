// dr_bench: what a client pays (bits per second) for how well it sees (error of the shown
// position against the truth), per dead-reckoning order, threshold, reconstruction and
// interest radius. NPCs walk waypoint paths with the zone's own movement system, avatars wander
// like client_stub players; the zone's sender decides and quantises the updates, the codec packs
// each observer's per-tick batch, and a client RemoteView reconstructs. Truth and shown
// positions are compared at the same server tick, which is what the report tool's join does.
//
// Usage: dr_bench [--seconds S] [--csv FILE] [--only SET]...   (SET: sweep, orient3, blend,
// loss10, loss10r, hb1s, radius, gather, quant, pertype, pertype_body)

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "clients/remote_view.h"
#include "clients/wander.h"
#include "common/interest_grid.h"
#include "common/rng.h"
#include "common/scene.h"
#include "wire/datagram_checksum.h"
#include "wire/downlink_frame.h"
#include "wire/wire_encode.h"
#include "zone_node/net/dead_reckoning.h"
#include "zone_node/population.h"
#include "zone_node/systems/avatar_movement.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/neighbourhood.h"
#include "zone_node/systems/npc_movement.h"
#include "zone_node/systems/rigid_bodies.h"

using namespace zonesim;

namespace {

constexpr int kNpcs = 600, kAvatars = 150;
// The pertype_body set adds debris: boxes in four piles, each thrown up every 2 s (one pile
// every 0.5 s) by a blast far below it, so at any time some fly on ballistic arcs, tumble, slide
// and settle, and some sleep. The blast's depth keeps the throws nearly vertical, so the piles
// spread slowly and stay within its reach for the whole run.
constexpr int kBodyPiles = 4, kBodiesPerPile = 60;
constexpr double kBlastEvery = 0.5;  // s between blasts, taking the piles in turn
constexpr double kBlastDepth = 50;   // m below the ground
constexpr double kUdpIpHeaderBytes = 28;
// Frames carry the server tick as LEB128: measured as for a server up an hour (3 bytes; 2 for
// the bench's own ticks would flatter it). A day adds a byte.
constexpr std::uint64_t kUptimeTicks = 30 * 3600;
constexpr std::uint64_t kToken = 0x1234567890abcdefULL;

struct Config {
  std::string name;
  DeadReckoningModel::Order order = DeadReckoningModel::Order::First;
  /// The avatars' own order (the scene's dead_reckoning.models.avatar); `order` when unset.
  std::optional<DeadReckoningModel::Order> avatar_order;
  /// The rigid bodies' order (dead_reckoning.models.rigid_body); unset: no bodies at all.
  std::optional<DeadReckoningModel::Order> body_order;
  bool body_rotating = true;  ///< orientation extrapolated with the angular velocity
  double threshold = 0.25;
  double heartbeat = 5;
  double orientation_deg = 3;
  bool blend = true;
  double loss = 0;
  /// Resend-until-acknowledged (wire/ack_window.h): a lost update, or one whose ack was
  /// lost, is sent again with the newest state after this timeout; 0 = never resent.
  double resend_rto_s = 0;
  double radius = 100;
  /// Ticks whose updates share one datagram per observer (the gateway gathering a send): only
  /// the newest state of each entity goes, and the client gets it at the send's tick.
  int ticks_per_datagram = 1;
  /// Wire resolution of positions (m per step within the interest cell) and of orientations
  /// (bits per smallest-three component): the quantisation knob.
  double position_resolution = 1.0 / 512;
  int rotation_bits = 10;
};

struct Result {
  double bits_per_client_s = 0, wire_bits_per_client_s = 0;
  double flat_wire_bits_per_client_s = 0;  ///< the same datagrams framed as FlatBuffers
  double visible_moving = 0;
  double p50 = 0, p99 = 0, max = 0;
  double updates_per_entity_s = 0;
  /// The same by entity type: p99 shown error and updates per entity per second.
  double p99_npc = 0, p99_avatar = 0, updates_npc_s = 0, updates_avatar_s = 0;
  double p99_body = 0, updates_body_s = 0;  ///< when the config has bodies
  double body_moving = 0;                   ///< share of the bodies' ticks at over 0.1 m/s
};

Scene benchScene() {
  Scene s;
  s.world = {{0, 0, 0}, {1000, 50, 1000}};
  s.dt = 1.0 / 30;
  s.tick_rate = 30;
  s.seed = 11;
  s.interest_cell_size = 50;
  NpcPopulation p;
  p.count = kNpcs;
  p.min_speed = 1.0;
  p.max_speed = 2.0;
  p.acceleration = 2.0;
  p.waypoint_radius = 40;
  p.region = s.world;
  s.npcs.push_back(p);
  return s;
}

// The debris of the pertype_body set, added to the bench scene for `seconds`.
void addDebris(Scene& s, double seconds) {
  const double centres[kBodyPiles][2] = {{250, 250}, {750, 250}, {250, 750}, {750, 750}};
  for (const auto& c : centres) {
    RigidBodyPopulation p;
    p.count = kBodiesPerPile;
    p.shape = RigidBodyPopulation::Shape::Box;
    p.size = {0.6, 0.6, 0.6};
    p.drop_height = 0.5;
    p.max_drop_height = 6;
    p.region = {{c[0] - 8, 0, c[1] - 8}, {c[0] + 8, 0, c[1] + 8}};
    s.rigid_bodies.push_back(p);
  }
  int k = 0;
  for (double t = 2; t < seconds; t += kBlastEvery, ++k) {
    SceneExplosion e;
    e.time = t;
    e.position = {centres[k % kBodyPiles][0], -kBlastDepth, centres[k % kBodyPiles][1]};
    e.radius = kBlastDepth + 10;  // reaches bodies within 33 m of the pile's centre
    e.falloff = SceneExplosion::Falloff::Constant;
    e.impulse = 6;  // N s on 1 kg boxes: 6 m/s, about 1.2 s in the air
    s.physics.explosions.push_back(e);
  }
}

double percentile(std::vector<double>& v, double q) {
  if (v.empty()) return 0;
  std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

// A gathered chunk as the gateway sends it: a lean StateBatch frame (the real encoder).
std::size_t leanBytes(const dr::PackedChunk& ch, std::uint64_t tick) {
  return gateway::encodeFrame({gateway::FrameKind::StateBatch, 1, tick + kUptimeTicks, ch.count},
                              ch.bytes, kToken)
      .size();
}

// The same chunk as the FlatBuffers Datagram{token, StateBatch} with its CRC-32C that carried
// it before the lean frame (its tables are still in idl/client_protocol.fbs), for comparison.
std::size_t flatBytes(const dr::PackedChunk& ch, std::uint64_t tick) {
  flatbuffers::FlatBufferBuilder fbb(gateway::kMaxDatagramBytes);
  auto v = fbb.CreateVector(ch.bytes.data(), ch.bytes.size());
  auto batch = proto::CreateStateBatch(fbb, tick + kUptimeTicks, std::uint16_t(ch.count), v, 1);
  proto::FinishDatagramBuffer(
      fbb, proto::CreateDatagram(fbb, kToken, proto::Message::StateBatch, batch.Union()));
  return fbb.GetSize() + gateway::kChecksumBytes;
}

// Bytes around one record's packed bytes, by each encoder.
std::size_t framingBytes(const dr::StateCodec& codec, bool lean) {
  dr::WireEntity e;
  e.id = 1;
  std::vector<dr::WireEntity> one{e};
  dr::PackedChunk ch = codec.pack(one, 0, gateway::kPackedBytesPerDatagram)[0];
  return (lean ? leanBytes(ch, 0) : flatBytes(ch, 0)) - ch.bytes.size();
}

Result run(const Config& c, double seconds) {
  Scene scene = benchScene();
  if (c.body_order) addDebris(scene, seconds);
  DeadReckoning& drc = scene.dead_reckoning;
  drc.position_threshold = c.threshold;
  drc.heartbeat_seconds = c.heartbeat;
  drc.orientation_threshold_deg = c.orientation_deg;
  drc.npc.order = drc.avatar.order = c.order;
  if (c.avatar_order) drc.avatar.order = *c.avatar_order;
  if (c.body_order) drc.rigid_body = {*c.body_order, c.body_rotating};
  drc.quantisation.position_resolution = c.position_resolution;
  drc.quantisation.rotation_bits = c.rotation_bits;
  zone::EntityStore store;
  zone::forEachInitialEntity(scene, [&](const zone::EntityRecordData& r) { store.add(r); });
  std::vector<clients::Wander> wanders;
  Pcg32 place(scene.seed, 99);
  for (int a = 0; a < kAvatars; ++a) {
    zone::EntityRecordData r;
    r.id = EntityId::make(1, std::uint64_t(a + 1));
    r.kind = zone::EntityKind::Avatar;
    r.pos = Vec3(place.uniform(0, 1000), 0, place.uniform(0, 1000));
    r.avatar.max_speed = 5.0;
    store.add(r);
    wanders.emplace_back(scene.world, 8.0, scene.seed, std::uint64_t(a));
  }
  InterestGrid grid(scene.world, scene.interest_cell_size);
  zone::DeadReckoner reckoner(drc, dr::codecParams(scene));
  const dr::StateCodec& codec = reckoner.codec();
  clients::RemoteView view({c.blend, 0.2, scene.dt});
  Pcg32 loss(5, 6);
  const int ticks = int(seconds / scene.dt);
  const int warmup = int(5 / scene.dt);  // let the first full sends pass
  std::vector<double> errors, errors_npc, errors_avatar, errors_body;
  errors.reserve(std::size_t(ticks) * store.size() / 2);
  double updates_npc = 0, updates_avatar = 0, updates_body = 0, body_moving = 0;
  double bits = 0, wire_bits = 0, flat_wire_bits = 0, visible_moving = 0, updates = 0;
  std::vector<int> observers;
  for (std::size_t i = 0; i < store.size(); ++i)
    if (store.kind[i] == zone::EntityKind::Avatar) observers.push_back(int(i));
  std::vector<dr::WireEntity> sent, batch;
  // Resend bookkeeping per entity: the newest state sent, and when to send it again (-1: acked).
  std::vector<dr::WireEntity> last(store.size());
  std::vector<int> resend_at(store.size(), -1);
  const int rto_ticks = std::max(1, int(std::lround(c.resend_rto_s / scene.dt)));
  // One delivery over the lossy link: the state reaches the client unless lost; the sender
  // hears of it unless the ack is lost too, and otherwise schedules a resend.
  auto deliver = [&](std::size_t i, const dr::WireEntity& w, int tick) {
    bool lost = c.loss > 0 && loss.uniform(0, 1) < c.loss;
    if (!lost) view.update(w, double(tick));
    bool ack_lost = c.resend_rto_s > 0 && loss.uniform(0, 1) < c.loss;
    resend_at[i] = c.resend_rto_s > 0 && (lost || ack_lost) ? tick + rto_ticks : -1;
  };
  std::vector<std::vector<char>> known(observers.size(), std::vector<char>(store.size(), 0));
  // Gathering over ticks_per_datagram ticks: what the client gets at the next send (the
  // newest state per entity, and whether it is a spawn), and each observer's gathered batch.
  const int k = std::max(1, c.ticks_per_datagram);
  std::vector<int> waiting(store.size(), 0);  // 0 none, 1 update, 2 spawn
  std::vector<dr::WireEntity> newest(store.size());
  std::vector<std::vector<dr::WireEntity>> gathered(observers.size());
  zone::WanderMovement wander(scene);
  zone::LoneZone lone{scene.dt};
  std::optional<zone::RigidBodySystem> bodies;
  if (c.body_order) bodies.emplace(scene, 0);
  for (int tick = 0; tick < ticks; ++tick) {
    double t = tick * scene.dt;
    for (int a = 0; a < kAvatars; ++a) {
      std::size_t i = std::size_t(observers[std::size_t(a)]);
      clients::Move m = wanders[std::size_t(a)].step(store.pos[i].x(), store.pos[i].z(), t);
      store.avatar[i].move_x = m.x;
      store.avatar[i].move_z = m.z;
    }
    lone.step(wander, store, std::uint64_t(tick));  // no separation
    if (bodies) lone.step(*bodies, store, std::uint64_t(tick));
    zone::stepAvatars(scene.world, store, scene.dt);
    // The zone's publish decision, as CellPublisher makes it.
    sent.clear();
    for (std::size_t i = 0; i < store.size(); ++i) {
      dr::State truth = zone::trueState(store, i, tick > 0 ? scene.dt : 0);
      zone::rememberTick(store, i);
      int cell = grid.cellOf(store.pos[i].x(), store.pos[i].z());
      zone::DeadReckoningState& d = store.dr[i];
      bool first = d.cell < 0;
      if (!first && reckoner.due(d, store.id[i], store.kind[i], truth, t) == dr::Due::None) {
        if (resend_at[i] == tick) {  // unacknowledged: the newest state again
          sent.push_back(last[i]);
          newest[i] = last[i];
          waiting[i] = std::max(waiting[i], 1);
        }
        continue;
      }
      d.cell = cell;
      dr::WireEntity w;
      w.id = store.id[i].value;
      w.kind = std::uint8_t(store.kind[i]);
      w.tick = std::uint64_t(tick);
      w.cell = cell;
      w.model = zone::modelFor(drc, store.kind[i]);
      w.state = reckoner.quantised(truth, store.kind[i], cell, &w.rot_largest);
      zone::DeadReckoner::markSent(d, w.state, t);
      sent.push_back(w);
      // The client; spawns are reliable, updates may be lost.
      last[i] = w;
      newest[i] = w;
      waiting[i] = first ? 2 : std::max(waiting[i], 1);
    }
    bool send_tick = (tick + 1) % k == 0;
    if (send_tick)
      for (std::size_t i = 0; i < store.size(); ++i) {
        if (waiting[i] == 2)
          view.spawn(newest[i], double(tick));
        else if (waiting[i] == 1)
          deliver(i, newest[i], tick);
        waiting[i] = 0;
      }
    if (tick < warmup) continue;
    updates += double(sent.size());
    for (const dr::WireEntity& w : sent)
      (w.kind == std::uint8_t(zone::EntityKind::Avatar)      ? updates_avatar
       : w.kind == std::uint8_t(zone::EntityKind::RigidBody) ? updates_body
                                                             : updates_npc) += 1;
    std::sort(sent.begin(), sent.end(), [](auto& a, auto& b) { return a.id < b.id; });
    // Each observer's batch: the updates of entities within its interest radius.
    double r2 = c.radius * c.radius;
    for (std::size_t ob = 0; ob < observers.size(); ++ob) {
      int o = observers[ob];
      double ox = store.pos[std::size_t(o)].x(), oz = store.pos[std::size_t(o)].z();
      std::vector<dr::WireEntity>& mine = gathered[ob];
      for (const dr::WireEntity& w : sent) {
        double dx = w.state.pos.x - ox, dz = w.state.pos.z - oz;
        if (dx * dx + dz * dz <= r2) mine.push_back(w);
      }
      std::vector<char>& seen = known[ob];
      for (std::size_t i = 0; i < store.size(); ++i) {
        double dx = store.pos[i].x() - ox, dz = store.pos[i].z() - oz;
        bool inside = dx * dx + dz * dz <= r2;
        if (inside && store.vel[i].norm() > 0.1 && int(i) != o) visible_moving += 1;
        // An entity entering the interest costs one full record (a Spawn); leaving, an id.
        if (inside && !seen[i]) {
          double b = codec.stateBits(zone::modelFor(drc, store.kind[i])) + 24;
          bits += b;
          wire_bits += b;
          flat_wire_bits += b;
        } else if (!inside && seen[i]) {
          bits += 64;
          wire_bits += 64;
          flat_wire_bits += 64;
        }
        seen[i] = inside;
      }
      if (!send_tick || mine.empty()) continue;
      // The send: the newest state of each entity gathered (ascending ids, newest first).
      std::sort(mine.begin(), mine.end(),
                [](auto& a, auto& b) { return a.id != b.id ? a.id < b.id : a.tick > b.tick; });
      batch.clear();
      for (const dr::WireEntity& w : mine)
        if (batch.empty() || batch.back().id != w.id) batch.push_back(w);
      mine.clear();
      for (const dr::PackedChunk& ch :
           codec.pack(batch, std::uint64_t(tick), gateway::kPackedBytesPerDatagram)) {
        bits += 8.0 * double(ch.bytes.size());
        wire_bits += 8.0 * (double(leanBytes(ch, std::uint64_t(tick))) + kUdpIpHeaderBytes);
        flat_wire_bits += 8.0 * (double(flatBytes(ch, std::uint64_t(tick))) + kUdpIpHeaderBytes);
      }
    }
    // What the client shows against the truth, for every entity, at this server tick.
    for (std::size_t i = 0; i < store.size(); ++i) {
      auto shown = view.shown(store.id[i].value, double(tick));
      if (!shown) continue;
      double dx = shown->x - store.pos[i].x(), dy = shown->y - store.pos[i].y(),
             dz = shown->z - store.pos[i].z();
      const double e = std::sqrt(dx * dx + dy * dy + dz * dz);
      errors.push_back(e);
      (store.kind[i] == zone::EntityKind::Avatar      ? errors_avatar
       : store.kind[i] == zone::EntityKind::RigidBody ? errors_body
                                                      : errors_npc)
          .push_back(e);
      if (store.kind[i] == zone::EntityKind::RigidBody) body_moving += store.vel[i].norm() > 0.1;
    }
  }
  double measured_s = (ticks - warmup) * scene.dt;
  double n_obs = double(observers.size());
  Result r;
  r.bits_per_client_s = bits / n_obs / measured_s;
  r.wire_bits_per_client_s = wire_bits / n_obs / measured_s;
  r.flat_wire_bits_per_client_s = flat_wire_bits / n_obs / measured_s;
  r.visible_moving = visible_moving / n_obs / double(ticks - warmup);
  r.updates_per_entity_s = updates / double(store.size()) / measured_s;
  r.max = errors.empty() ? 0 : *std::max_element(errors.begin(), errors.end());
  r.p50 = percentile(errors, 0.5);
  r.p99 = percentile(errors, 0.99);
  r.p99_npc = percentile(errors_npc, 0.99);
  r.p99_avatar = percentile(errors_avatar, 0.99);
  r.updates_npc_s = updates_npc / double(kNpcs) / measured_s;
  r.updates_avatar_s = updates_avatar / double(kAvatars) / measured_s;
  if (c.body_order) {
    r.p99_body = percentile(errors_body, 0.99);
    r.updates_body_s = updates_body / double(kBodyPiles * kBodiesPerPile) / measured_s;
    r.body_moving = errors_body.empty() ? 0 : body_moving / double(errors_body.size());
  }
  return r;
}

const char* orderName(DeadReckoningModel::Order o) {
  switch (o) {
    case DeadReckoningModel::Order::Static:
      return "static";
    case DeadReckoningModel::Order::First:
      return "first";
    case DeadReckoningModel::Order::Second:
      return "second";
  }
  return "?";
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 60;
  std::string csv_path;
  std::vector<std::string> only;  // --only SET (repeatable): run just these sets
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc) seconds = std::atof(argv[++i]);
    if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only.push_back(argv[++i]);
  }
  std::vector<Config> configs;
  using O = DeadReckoningModel::Order;
  // The sweep isolates the position threshold (orientation threshold off) and shows the
  // model's own error (snap); the rows after it change one thing at a time from first order,
  // 0.25 m, snap.
  for (O order : {O::Static, O::First, O::Second})
    for (double th : {0.05, 0.1, 0.25, 0.5, 1.0}) {
      Config c;
      c.name = "sweep";
      c.order = order;
      c.threshold = th;
      c.orientation_deg = 180;
      c.blend = false;
      configs.push_back(c);
    }
  Config base;
  base.orientation_deg = 180;
  base.blend = false;
  Config c = base;
  c.name = "orient3";
  c.orientation_deg = 3;
  configs.push_back(c);
  c = base;
  c.name = "blend";
  c.blend = true;
  configs.push_back(c);
  c = base;
  c.name = "loss10";
  c.loss = 0.1;
  configs.push_back(c);
  c = base;
  c.name = "loss10r";
  c.loss = 0.1;
  c.resend_rto_s = 0.1;  // RTT (loopback plus a 30 Hz tick) + the 50 ms between acks
  configs.push_back(c);
  c = base;
  c.name = "hb1s";
  c.heartbeat = 1;
  c.loss = 0.1;
  configs.push_back(c);
  for (double radius : {25.0, 50.0, 100.0, 150.0, 200.0}) {
    c = base;
    c.name = "radius";
    c.radius = radius;
    configs.push_back(c);
  }
  // Several ticks' updates in one datagram: framing per visible entity against the latency.
  for (int ticks : {1, 2, 3, 4, 5}) {
    c = base;
    c.name = "gather";
    c.ticks_per_datagram = ticks;
    configs.push_back(c);
  }
  // Quantisation: coarser positions and orientations cost fewer bits per update, and add their
  // rounding to the shown error (first order, 0.25 m, as the rows above).
  for (auto [resolution, bits] :
       {std::pair{1.0 / 32, 6}, std::pair{1.0 / 64, 7}, std::pair{1.0 / 128, 8},
        std::pair{1.0 / 256, 9}, std::pair{1.0 / 512, 10}, std::pair{1.0 / 2048, 12}}) {
    c = base;
    c.name = "quant";
    c.position_resolution = resolution;
    c.rotation_bits = bits;
    configs.push_back(c);
  }
  // Per entity type: NPCs (waypoint walkers, 1-2 m/s, smooth) and avatars (players' wander,
  // 5 m/s, turning at will) each with its own order, at three thresholds; the error and the
  // update rate are reported per type.
  for (double th : {0.1, 0.25, 0.5})
    for (O npc : {O::Static, O::First, O::Second})
      for (O avatar : {O::First, O::Second}) {
        c = base;
        c.name = "pertype";
        c.threshold = th;
        c.order = npc;
        c.avatar_order = avatar;
        configs.push_back(c);
      }
  // Rigid bodies (blown-up debris: arcs under gravity, tumbling, sliding, sleep) with their own
  // order at the same thresholds; NPCs and avatars stay at first order. The orientation
  // threshold is off (as in every row from `base`), so the spin does not matter here.
  for (double th : {0.1, 0.25, 0.5}) {
    for (O body : {O::Static, O::First, O::Second}) {
      c = base;
      c.name = "pertype_body";
      c.threshold = th;
      c.avatar_order = O::First;
      c.body_order = body;
      configs.push_back(c);
    }
  }
  if (!only.empty())
    std::erase_if(configs, [&](const Config& c) {
      return std::find(only.begin(), only.end(), c.name) == only.end();
    });
  FILE* csv = csv_path.empty() ? nullptr : std::fopen(csv_path.c_str(), "w");
  if (csv)
    std::fprintf(csv,
                 "set,order,threshold_m,blend,loss,radius_m,payload_bps,wire_bps,visible_moving,"
                 "bps_per_visible,p50_m,p99_m,max_m,updates_per_entity_s,ticks_per_datagram,"
                 "wire_bps_per_visible,flatbuffers_wire_bps_per_visible,position_resolution_m,"
                 "rotation_bits,avatar_order,p99_npc_m,p99_avatar_m,updates_per_npc_s,"
                 "updates_per_avatar_s,body_order,body_rotating,p99_body_m,updates_per_body_s,body_"
                 "moving\n");
  std::printf(
      "%d NPCs (1-2 m/s, waypoint paths) + %d wandering avatars (5 m/s) in 1 km^2, 30 Hz, "
      "%.0f s measured after 5 s; heartbeat 5 s unless hb1s\n",
      kNpcs, kAvatars, seconds - 5);
  dr::StateCodec bench_codec(dr::codecParams(benchScene()));
  std::printf(
      "framing: %zu B per datagram around its packed records as a lean frame (FlatBuffers "
      "Datagram: %zu B), at server tick %llu, plus %.0f B of UDP/IP\n",
      framingBytes(bench_codec, true), framingBytes(bench_codec, false),
      static_cast<unsigned long long>(kUptimeTicks), kUdpIpHeaderBytes);
  std::printf(
      "%-7s %-6s %6s %5s %5s %6s %3s %6s %3s | %10s %10s %8s %9s %9s %9s | %8s %8s %8s | %7s\n",
      "set", "order", "thr_m", "blend", "loss", "rad_m", "tpd", "pos_mm", "rot", "payload/s",
      "wire b/s", "visible", "b/s/vis", "wire/vis", "fb w/vis", "p50_m", "p99_m", "max_m",
      "upd/e/s");
  for (const Config& c : configs) {
    Result r = run(c, seconds);
    double per_visible = r.visible_moving > 0 ? r.bits_per_client_s / r.visible_moving : 0;
    double wire_per_visible =
        r.visible_moving > 0 ? r.wire_bits_per_client_s / r.visible_moving : 0;
    double flat_per_visible =
        r.visible_moving > 0 ? r.flat_wire_bits_per_client_s / r.visible_moving : 0;
    std::printf(
        "%-7s %-6s %6.2f %5d %5.2f %6.0f %3d %6.2f %3d | %10.0f %10.0f %8.1f %9.1f %9.1f %9.1f | "
        "%8.4f %8.4f %8.3f | %7.3f\n",
        c.name.c_str(), orderName(c.order), c.threshold, int(c.blend), c.loss, c.radius,
        c.ticks_per_datagram, 1000.0 * c.position_resolution, c.rotation_bits, r.bits_per_client_s,
        r.wire_bits_per_client_s, r.visible_moving, per_visible, wire_per_visible, flat_per_visible,
        r.p50, r.p99, r.max, r.updates_per_entity_s);
    if (c.avatar_order) {
      std::printf(
          "        by type: npc %-6s p99 %.4f m, %.3f updates/s; avatar %-6s p99 %.4f m, %.3f "
          "updates/s\n",
          orderName(c.order), r.p99_npc, r.updates_npc_s, orderName(*c.avatar_order), r.p99_avatar,
          r.updates_avatar_s);
    }
    if (c.body_order)
      std::printf(
          "        rigid bodies: %-6s p99 %.4f m, %.3f updates/s (moving %.1f %% of ticks)\n",
          orderName(*c.body_order), r.p99_body, r.updates_body_s, 100 * r.body_moving);
    std::fflush(stdout);
    if (csv)
      std::fprintf(csv,
                   "%s,%s,%g,%d,%g,%g,%.1f,%.1f,%.2f,%.2f,%.5f,%.5f,%.4f,%.4f,%d,%.2f,%.2f,%g,%d,"
                   "%s,%.5f,%.5f,%.4f,%.4f,%s,%d,%.5f,%.4f,%.4f\n",
                   c.name.c_str(), orderName(c.order), c.threshold, int(c.blend), c.loss, c.radius,
                   r.bits_per_client_s, r.wire_bits_per_client_s, r.visible_moving, per_visible,
                   r.p50, r.p99, r.max, r.updates_per_entity_s, c.ticks_per_datagram,
                   wire_per_visible, flat_per_visible, c.position_resolution, c.rotation_bits,
                   orderName(c.avatar_order.value_or(c.order)), r.p99_npc, r.p99_avatar,
                   r.updates_npc_s, r.updates_avatar_s,
                   c.body_order ? orderName(*c.body_order) : "", int(c.body_rotating), r.p99_body,
                   r.updates_body_s, r.body_moving);
  }
  if (csv) std::fclose(csv);
  return 0;
}
