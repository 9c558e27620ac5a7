// Two bodies owned by two ranks collide across the zone border (run under mpirun -np 2): the
// rank holding the lower id solves their island with both bodies and sends the other back, so
// the outcome is bit for bit that of one world holding both, and momentum is conserved.
#include <gtest/gtest.h>
#include <mpi.h>

#include "common/scene.h"
#include "zone_node/cluster/byte_exchange.h"
#include "zone_node/cluster/migration.h"
#include "zone_node/cluster/value_gather.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/rigid_bodies.h"

namespace zonesim::zone {
namespace {

Scene borderScene() {
  Scene s;
  s.world = {{0, 0, 0}, {100, 50, 100}};
  s.dt = 1.0 / 60;
  s.zones.columns = 2;
  s.zones.rows = 1;
  s.halo_width = 4;
  return s;
}

/// Sphere A (1 kg) heads +x from rank 0's side, B (3 kg) heads -x from rank 1's side, high above
/// the ground so that nothing but their contact acts sideways.
EntityRecordData sphere(std::uint32_t creator, double x, double vx, double mass) {
  EntityRecordData r;
  r.id = EntityId::make(creator, 1);
  r.kind = EntityKind::RigidBody;
  r.pos = Vec3(x, 30, 50.2);
  r.vel = Vec3(vx, 0, 0);
  r.body.shape = BodyData::Sphere;
  r.body.radius = 0.5;
  r.body.mass = mass;
  r.body.restitution = 1.0;
  r.body.friction = 0.0;
  return r;
}

struct Totals {
  Vec3 momentum = Vec3::Zero();
  double va = 0, vb = 0;
};

/// This rank's zone of a 2 x 1 layout, stepped as zone_node steps it: the island exchange over
/// MPI, then migration.
struct ClusterZone {
  ClusterZone(const Scene& scene, int rank)
      : layout(scene.world, 2, 1),
        migrator(MPI_COMM_WORLD, rank, 2),
        bytes(MPI_COMM_WORLD, 2),
        zone{scene.dt} {
    zone.cluster.gather = [](const std::vector<std::uint64_t>& v) {
      return gatherValues(MPI_COMM_WORLD, v);
    };
    zone.cluster.swap = [this](const std::vector<std::vector<std::uint8_t>>& out) {
      return bytes.swap(out);
    };
    zone.cluster.rank = rank;
    zone.cluster.ranks = 2;
    zone.cluster.zone = layout.rect(rank);
  }
  ClusterZone(const ClusterZone&) = delete;  // the exchange's lambda points at this one

  /// Tick t; returns its counters.
  TickCounters step(RigidBodySystem& bodies, EntityStore& store, int t) {
    const TickCounters c = zone.step(bodies, store, std::uint64_t(t));
    migrator.exchange(store, layout, std::uint64_t(t), forward);
    return c;
  }

  ZoneLayout layout;
  Migrator migrator;
  ByteExchange bytes;
  LoneZone zone;
  std::vector<std::vector<ForwardedInput>> forward = std::vector<std::vector<ForwardedInput>>(2);
};

/// The sum of `v` over the ranks.
std::uint64_t clusterSum(std::uint64_t v) {
  std::uint64_t all = 0;
  MPI_Allreduce(&v, &all, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  return all;
}

/// Every body this rank holds ends bit for bit where it ends in `one`, a world holding them all.
void expectAsOneWorld(const EntityStore& store, const EntityStore& one) {
  for (std::size_t i = 0; i < store.size(); ++i) {
    const std::size_t k = *one.indexOf(store.id[i]);
    EXPECT_EQ(store.pos[i], one.pos[k]) << toString(store.id[i]);
    EXPECT_EQ(store.vel[i], one.vel[k]) << toString(store.id[i]);
    EXPECT_EQ(store.rot[i].coeffs(), one.rot[k].coeffs()) << toString(store.id[i]);
  }
}

Totals totals(const EntityStore& store, MPI_Comm comm) {
  double local[5] = {0, 0, 0, 0, 0};
  for (std::size_t i = 0; i < store.size(); ++i) {
    Vec3 p = store.vel[i] * store.body[i].mass;
    for (int k = 0; k < 3; ++k) local[k] += p[k];
    local[store.id[i].creatorRank() == 0 ? 3 : 4] += store.vel[i].x();
  }
  double global[5];
  MPI_Allreduce(local, global, 5, MPI_DOUBLE, MPI_SUM, comm);
  return {Vec3(global[0], global[1], global[2]), global[3], global[4]};
}

TEST(BorderContact, TwoZonesEndBitForBitAsOneWorld) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_EQ(size, 2) << "run with mpirun -np 2";
  const Scene scene = borderScene();
  const double kA = 1.0, kB = 3.0, kSpeed = 4.0;
  const int kTicks = 40;

  // The reference: one world holding both bodies (computed on every rank alike).
  EntityStore one;
  one.add(sphere(0, 48.0, kSpeed, kA));
  one.add(sphere(1, 52.0, -kSpeed, kB));
  RigidBodySystem single(scene, 0);
  LoneZone lone{scene.dt};
  for (int t = 0; t < kTicks; ++t) lone.step(single, one, std::uint64_t(t));

  // Two zones, each owning one body, stepping as zone_node does: the island exchange, then
  // migration.
  EntityStore store;
  store.add(rank == 0 ? sphere(0, 48.0, kSpeed, kA) : sphere(1, 52.0, -kSpeed, kB));
  ClusterZone zone(scene, rank);
  RigidBodySystem bodies(scene, rank);
  const Totals before = totals(store, MPI_COMM_WORLD);
  std::uint64_t shared = 0;
  for (int t = 0; t < kTicks; ++t) shared += zone.step(bodies, store, t).island_bodies_in;
  const Totals after = totals(store, MPI_COMM_WORLD);
  EXPECT_GT(clusterSum(shared), 0u) << "the two bodies were solved together on one rank";

  // Bit for bit one world's end, wherever each body ended.
  expectAsOneWorld(store, one);

  // Sideways momentum is untouched by gravity: conserved to round-off across the exchange. The
  // scene's solver, the default wide soft step, solves velocities in float: round-off is float's
  // (7e-7 of 16 kg m/s measured; Gauss-Seidel in double holds 1e-12).
  const double round_off = 1e-6;
  EXPECT_NEAR(after.momentum.x(), before.momentum.x(), round_off * (kA + kB) * kSpeed);
  EXPECT_NEAR(after.momentum.z(), before.momentum.z(), round_off * (kA + kB) * kSpeed);
  // Vertically only gravity acts: -(mA + mB) g t.
  const double fallen = (kA + kB) * 9.81 * kTicks * scene.dt;
  EXPECT_NEAR(after.momentum.y() - before.momentum.y(), -fallen, round_off * fallen);
  // Elastic, 1 kg at +4 against 3 kg at -4: A leaves at -8, B stops (analytic).
  EXPECT_NEAR(after.va, -8.0, 0.05 * 8.0);
  EXPECT_NEAR(after.vb, 0.0, 0.05 * 8.0);
  if (rank == 0)
    std::printf("two ranks: vA %.6f vB %.6f; one world: vA %.6f vB %.6f; momentum x %.3e -> %.3e\n",
                after.va, after.vb, one.vel[*one.indexOf(EntityId::make(0, 1))].x(),
                one.vel[*one.indexOf(EntityId::make(1, 1))].x(), before.momentum.x(),
                after.momentum.x());
}

TEST(BorderContact, FarIslandsEndBitForBitAsOneWorldUnderLevelOfDetail) {
  // No player anywhere: every island steps every 4th tick (lod.physics_every), by the 4 ticks
  // it owed. Three spheres fall together across the border and part again, so the worlds
  // holding them are rebuilt mid-period: the ticks each body owes travel with it, and every
  // world numbers its steps by the tick, so all step on the ticks one world would.
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_EQ(size, 2) << "run with mpirun -np 2";
  Scene scene = borderScene();
  scene.lod.enabled = true;
  scene.lod.physics_every = 4;
  const int kTicks = 90;
  auto spheres = [](int owner) {
    std::vector<EntityRecordData> out;
    const double xs[] = {47.0, 53.0, 50.6};
    const double vxs[] = {3.0, -3.0, 0.0};
    for (int k = 0; k < 3; ++k) {
      EntityRecordData r = sphere(std::uint32_t(k), xs[k], vxs[k], 1.0 + k);
      r.id = EntityId::make(std::uint32_t(k), 1);
      r.pos.y() = 2.0 + 0.5 * k;
      r.body.restitution = 0.5;
      r.body.friction = 0.5;
      if (owner < 0 || (r.pos.x() < 50.0) == (owner == 0)) out.push_back(r);
    }
    return out;
  };
  EntityStore one;
  for (const EntityRecordData& r : spheres(-1)) one.add(r);
  RigidBodySystem single(scene, 0);
  LoneZone lone{scene.dt};
  std::uint64_t held = 0;
  for (int t = 0; t < kTicks; ++t) held += lone.step(single, one, std::uint64_t(t)).bodies_held;
  EXPECT_GT(held, 100u) << "far bodies waited for their island's step";

  EntityStore store;
  for (const EntityRecordData& r : spheres(rank)) store.add(r);
  ClusterZone zone(scene, rank);
  RigidBodySystem bodies(scene, rank);
  std::uint64_t traded = 0;
  for (int t = 0; t < kTicks; ++t) traded += zone.step(bodies, store, t).island_bodies_in;
  EXPECT_GT(clusterSum(traded), 0u) << "an island crossed the border";
  expectAsOneWorld(store, one);
}

TEST(BorderContact, ASleepingClusterTradesNoBodies) {
  // Two spheres dropped onto the ground either side of the border, touching across it: they
  // settle and fall asleep, and from then on no zone finds islands or trades bodies (one
  // gather a tick tells every zone that nothing anywhere is awake).
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_EQ(size, 2) << "run with mpirun -np 2";
  const Scene scene = borderScene();
  ASSERT_TRUE(scene.physics.sleep);
  EntityRecordData mine = sphere(std::uint32_t(rank), rank == 0 ? 49.5 : 50.5, 0.0, 1.0);
  mine.pos.y() = 0.6;
  mine.body.restitution = 0.0;
  mine.body.friction = 0.5;
  EntityStore store;
  store.add(mine);
  ClusterZone zone(scene, rank);
  RigidBodySystem bodies(scene, rank);
  std::uint64_t early = 0, late = 0, shared = 0;
  for (int t = 0; t < 300; ++t) {
    const TickCounters c = zone.step(bodies, store, t);
    (t < 30 ? early : t >= 200 ? late : shared) += c.island_exchanges;
  }
  EXPECT_EQ(early, 30u) << "while the spheres fall and settle, islands are found every tick";
  EXPECT_TRUE(store.body[0].sleeping);
  EXPECT_EQ(late, 0u) << "asleep everywhere: no islands found, no bodies traded";
}

}  // namespace
}  // namespace zonesim::zone
