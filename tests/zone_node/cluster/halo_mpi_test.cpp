// Ghosts on 4 real ranks (run under mpirun): every entity within the halo width of a zone is a
// ghost there, bitwise equal to its owner's copy; send lists survive small motion and are
// rebuilt when entities move far, come and go, or the boundaries move.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>

#include "common/rng.h"
#include "zone_node/cluster/halo.h"

namespace zonesim::zone {
namespace {

struct Flat {
  std::uint64_t id;
  double x, y, z, vx, vy, vz;
};

/// Every rank's entities, on every rank.
std::vector<Flat> gatherAll(const EntityStore& s) {
  std::vector<Flat> mine;
  for (std::size_t i = 0; i < s.size(); ++i)
    mine.push_back({s.id[i].value, s.pos[i].x(), s.pos[i].y(), s.pos[i].z(), s.vel[i].x(),
                    s.vel[i].y(), s.vel[i].z()});
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int n = int(mine.size() * sizeof(Flat));
  std::vector<int> counts(static_cast<std::size_t>(size)), displs(static_cast<std::size_t>(size));
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  int total = 0;
  for (int r = 0; r < size; ++r) {
    displs[std::size_t(r)] = total;
    total += counts[std::size_t(r)];
  }
  std::vector<Flat> all(std::size_t(total) / sizeof(Flat));
  MPI_Allgatherv(mine.data(), n, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE,
                 MPI_COMM_WORLD);
  return all;
}

class HaloTest : public ::testing::Test {
 protected:
  void SetUp() override {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    ASSERT_EQ(size_, 4) << "run with mpirun -np 4";
    Pcg32 rng(42, std::uint64_t(rank_));
    ZoneRect r = layout_.rect(rank_);
    for (int i = 0; i < 400; ++i) {
      EntityRecordData e;
      e.id = EntityId::make(std::uint32_t(rank_), std::uint64_t(i + 1));
      e.kind = i % 3 == 0 ? EntityKind::RigidBody : EntityKind::Npc;
      e.pos = Vec3(rng.uniform(r.min_x, r.max_x), rng.uniform(0, 5), rng.uniform(r.min_z, r.max_z));
      e.vel = Vec3(rng.uniform(-1, 1), 0, rng.uniform(-1, 1));
      e.body.radius = 0.25 + 0.001 * i;
      store_.add(e);
    }
  }

  /// Every ghost is another rank's entity within width + skin, with its exact state, and every
  /// entity of another rank within width is a ghost.
  void expectGhostsExact(const HaloExchange& halo, const ZoneLayout& layout) {
    const GhostStore& g = halo.ghosts();
    ZoneRect mine = layout.rect(rank_);
    std::size_t within = 0;
    for (const Flat& f : gatherAll(store_)) {
      if (EntityId{f.id}.creatorRank() == std::uint32_t(rank_) && store_.indexOf(EntityId{f.id}))
        continue;
      double d = mine.distanceTo(f.x, f.z);
      std::optional<std::size_t> gi = g.indexOf(EntityId{f.id});
      if (d < kWidth) {
        ++within;
        ASSERT_TRUE(gi) << "entity " << f.id << " at " << d << " m is not a ghost on " << rank_;
      }
      if (!gi) continue;
      EXPECT_LT(d, kWidth + 1.5 * kSkin);  // reused lists: up to skin/2 of motion since built
      EXPECT_EQ(g.pos[*gi].x(), f.x);
      EXPECT_EQ(g.pos[*gi].y(), f.y);
      EXPECT_EQ(g.pos[*gi].z(), f.z);
      EXPECT_EQ(g.vel[*gi].x(), f.vx);
      EXPECT_EQ(g.vel[*gi].z(), f.vz);
    }
    EXPECT_GT(within, 10u) << "the test should put entities near the borders";
  }

  static constexpr double kWidth = 4.0, kSkin = 1.0;
  int rank_ = 0, size_ = 1;
  ZoneLayout layout_{SceneBox{{0, 0, 0}, {100, 10, 100}}, 2, 2};
  EntityStore store_;
};

TEST_F(HaloTest, GhostsAreExactlyTheNeighboursWithinTheWidth) {
  HaloExchange halo(MPI_COMM_WORLD, rank_, size_, kWidth, kSkin);
  HaloStats s = halo.refresh(store_, layout_, 0);
  EXPECT_TRUE(s.rebuilt);
  expectGhostsExact(halo, layout_);
  // Rigid-body ghosts carry their shape.
  const GhostStore& g = halo.ghosts();
  for (std::size_t i = 0; i < g.size(); ++i)
    if (g.kind[i] == EntityKind::RigidBody) {
      EXPECT_GE(g.body[i].radius, 0.25);
      EXPECT_EQ(g.owner[i], int(g.id[i].creatorRank()));
    }
}

TEST_F(HaloTest, ListsSurviveSmallMotionAndRebuildOnLargeMotion) {
  HaloExchange halo(MPI_COMM_WORLD, rank_, size_, kWidth, kSkin);
  halo.refresh(store_, layout_, 0);
  for (Vec3& p : store_.pos) p.x() += 0.4 * kSkin;  // under skin/2: lists still valid
  HaloStats s = halo.refresh(store_, layout_, 0);
  EXPECT_FALSE(s.rebuilt);
  // The old lists, reused, still cover everything within the width and carry the new state.
  expectGhostsExact(halo, layout_);
  for (Vec3& p : store_.pos) p.x() -= 0.4 * kSkin;
  store_.pos[0].z() += 0.6 * kSkin;  // one entity past skin/2: this rank rebuilds
  s = halo.refresh(store_, layout_, 0);
  EXPECT_TRUE(s.rebuilt);
  expectGhostsExact(halo, layout_);
}

TEST_F(HaloTest, RebuildsWhenEntitiesComeAndGoOrBoundariesMove) {
  HaloExchange halo(MPI_COMM_WORLD, rank_, size_, kWidth, kSkin);
  halo.refresh(store_, layout_, 0);
  store_.removeAt(5);
  HaloStats s = halo.refresh(store_, layout_, 0);
  EXPECT_TRUE(s.rebuilt);
  expectGhostsExact(halo, layout_);

  ZoneLayout moved = layout_;
  std::vector<double> cost = {4, 1, 1, 1};
  moved.rebalance(cost, 0.5, 10);
  s = halo.refresh(store_, moved, 1);
  EXPECT_TRUE(s.rebuilt);
  // Entities now outside their owner's zone still count as the owner's: ghosts follow owners.
  const GhostStore& g = halo.ghosts();
  ZoneRect mine = moved.rect(rank_);
  for (std::size_t i = 0; i < g.size(); ++i)
    EXPECT_LT(mine.distanceTo(g.pos[i].x(), g.pos[i].z()), kWidth + kSkin);
}

}  // namespace
}  // namespace zonesim::zone
