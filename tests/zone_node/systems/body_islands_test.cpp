// Which rank solves which rigid-body island: islands joined within a zone by overlapping reach
// boxes, then across zones from the bodies each zone shares, the lowest id deciding.
#include "zone_node/systems/body_islands.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace zonesim::zone {
namespace {

physics::Aabb boxAt(double x, double z, double half = 0.5) {
  return {Vec3(x - half, 0, z - half), Vec3(x + half, 1, z + half)};
}

EntityId id(std::uint64_t n) {
  return EntityId::make(0, n);
}

TEST(BodyIslands, OverlappingBoxesShareTheirLowestId) {
  // 1-2-3 in a chain (each touches the next only), 4 alone, 5-6 touching.
  const std::vector<EntityId> ids = {id(1), id(2), id(3), id(4), id(5), id(6)};
  const std::vector<physics::Aabb> boxes = {boxAt(0, 0),  boxAt(0.9, 0), boxAt(1.8, 0),
                                            boxAt(10, 0), boxAt(20, 0),  boxAt(20, 0.5)};
  const std::vector<EntityId> label = joinOverlapping(ids, boxes);
  EXPECT_EQ(label, (std::vector<EntityId>{id(1), id(1), id(1), id(4), id(5), id(5)}));
}

TEST(BodyIslands, TheLowestIdWinsWhateverTheBoxOrder) {
  // The chain's lowest id lies at its far end from the sweep's start.
  const std::vector<EntityId> ids = {id(1), id(2), id(3)};
  const std::vector<physics::Aabb> boxes = {boxAt(1.8, 0), boxAt(0.9, 0), boxAt(0, 0)};
  EXPECT_EQ(joinOverlapping(ids, boxes), (std::vector<EntityId>{id(1), id(1), id(1)}));
}

TEST(BodyIslands, IslandsJoinAcrossZonesThroughOverlappingBorderBodies) {
  // Zone 0's island 7 touches zone 1's island 3 at the border x = 50; zone 1's island 3 also
  // touches zone 2's island 12 at z = 50. Zone 2's island 20 is near a border but alone.
  const EntityId z0 = EntityId::make(0, 7), z1 = EntityId::make(1, 3), z2 = EntityId::make(2, 12),
                 alone = EntityId::make(2, 20);
  const std::vector<BorderBody> shared = {{z0, z0, 0, boxAt(49.6, 10)},
                                          {z1, EntityId::make(1, 4), 1, boxAt(50.4, 10)},
                                          {z1, EntityId::make(1, 5), 1, boxAt(50.4, 49.6)},
                                          {z2, z2, 2, boxAt(50.4, 50.4)},
                                          {alone, alone, 2, boxAt(80, 50.4)}};
  const auto solver = joinAcrossZones(shared);
  ASSERT_EQ(solver.size(), 4u);
  // The whole island's lowest id is zone 0's (creator rank 0 sorts first): zone 0 solves it.
  for (EntityId label : {z0, z1, z2}) {
    EXPECT_EQ(solver.at(label.value).island, z0) << toString(label);
    EXPECT_EQ(solver.at(label.value).rank, 0) << toString(label);
  }
  EXPECT_EQ(solver.at(alone.value).island, alone);
  EXPECT_EQ(solver.at(alone.value).rank, 2);
}

TEST(BodyIslands, BodiesOfOneZoneDoNotJoinItsIslandsAgain) {
  // Two islands of zone 0 whose shared boxes overlap: zone 0 found them apart (its reach boxes
  // are what it joined), and one zone's list must not overrule it.
  const std::vector<BorderBody> shared = {{id(1), id(1), 0, boxAt(49.6, 10)},
                                          {id(2), id(2), 0, boxAt(49.6, 10.5)}};
  const auto solver = joinAcrossZones(shared);
  EXPECT_EQ(solver.at(id(1).value).island, id(1));
  EXPECT_EQ(solver.at(id(2).value).island, id(2));
}

TEST(BodyIslands, JointsLinkIslandsWhereverTheirBodiesAre) {
  // Bodies 4 (zone 1) and 9 (zone 3) are jointed, far apart; 6 (zone 2) is not.
  const EntityId a = EntityId::make(1, 4), b = EntityId::make(3, 9), c = EntityId::make(2, 6);
  const std::vector<BorderBody> shared = {
      {a, a, 1, boxAt(10, 10)}, {b, b, 3, boxAt(90, 90)}, {c, c, 2, boxAt(50, 50)}};
  const std::vector<BodyLink> links = {{a, b}};
  const auto solver = joinAcrossZones(shared, links);
  EXPECT_EQ(solver.at(b.value).island, a);
  EXPECT_EQ(solver.at(b.value).rank, 1);
  EXPECT_EQ(solver.at(c.value).island, c);
  // Within a zone, links join by index.
  const std::vector<IndexLink> local = {{0, 2}};
  EXPECT_EQ(
      joinOverlapping(std::vector<EntityId>{id(1), id(2), id(3)},
                      std::vector<physics::Aabb>{boxAt(0, 0), boxAt(10, 0), boxAt(20, 0)}, local),
      (std::vector<EntityId>{id(1), id(2), id(1)}));
}

TEST(BodyIslands, AClothIslandSortsBelowEveryBody) {
  // A cloth's record has label 0: the bodies that may touch it, on any rank, are solved on
  // the cloth's rank.
  const EntityId a = EntityId::make(0, 1);
  const std::vector<BorderBody> shared = {{EntityId{}, EntityId{}, 3, boxAt(50, 50, 2)},
                                          {a, a, 0, boxAt(49, 49)}};
  const auto solver = joinAcrossZones(shared);
  EXPECT_EQ(solver.at(a.value).island, EntityId{});
  EXPECT_EQ(solver.at(a.value).rank, 3);
}

TEST(BodyIslands, BorderBodiesRoundTripThroughGatheredWordsBitForBit) {
  const std::vector<BorderBody> bodies = {{id(5), id(6), 3, boxAt(0.1, -7.3, 0.123456789)},
                                          {EntityId::make(9, 1), id(2), 0, boxAt(1e-300, 5e10)}};
  std::vector<std::uint64_t> words;
  for (const BorderBody& b : bodies) appendWords(b, words);
  EXPECT_EQ(words.size(), 2 * kBorderBodyWords);
  const std::vector<BorderBody> back = borderBodiesOf(words);
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back[i].label, bodies[i].label);
    EXPECT_EQ(back[i].body, bodies[i].body);
    EXPECT_EQ(back[i].rank, bodies[i].rank);
    EXPECT_EQ(back[i].box.lo, bodies[i].box.lo);
    EXPECT_EQ(back[i].box.hi, bodies[i].box.hi);
  }
  words.pop_back();
  EXPECT_THROW(borderBodiesOf(words), std::runtime_error);
}

}  // namespace
}  // namespace zonesim::zone
