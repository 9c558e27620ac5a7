#include "zone_node/ghost_store.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace zonesim::zone {
namespace {

TEST(GhostStore, RegisteredColumnsHoldOneValuePerGhostAndANameRegistersOnce) {
  GhostStore ghosts;
  const std::size_t crowd = ghosts.addColumn(crowdPopulationColumn());
  const std::size_t agent = ghosts.addColumn(agentTypeColumn());
  EXPECT_EQ(ghosts.addColumn(crowdPopulationColumn()), crowd) << "flocks and flows share it";
  ASSERT_EQ(ghosts.columns().size(), 2u);
  EXPECT_EQ(ghosts.columnIndex(kAgentType), agent);
  EXPECT_FALSE(ghosts.columnIndex("no.such").has_value());

  const std::vector<std::int64_t> first{3, -1}, second{-1, 2};
  ghosts.add(EntityId{10}, EntityKind::Npc, Vec3::Zero(), Vec3::Zero(), Quat::Identity(),
             BodyData{}, 1, first);
  ghosts.add(EntityId{11}, EntityKind::Npc, Vec3::Zero(), Vec3::Zero(), Quat::Identity(),
             BodyData{}, 2, second);
  ghosts.add(EntityId{12}, EntityKind::RigidBody, Vec3::Zero(), Vec3::Zero(), Quat::Identity(),
             BodyData{}, 2);  // no values given: none of them applies
  EXPECT_EQ(ghosts.value(crowd, 0), 3);
  EXPECT_EQ(ghosts.value(agent, 0), -1);
  EXPECT_EQ(ghosts.value(crowd, 1), -1);
  EXPECT_EQ(ghosts.value(agent, 1), 2);
  EXPECT_EQ(ghosts.value(crowd, 2), -1);
  ghosts.clear();
  EXPECT_EQ(ghosts.size(), 0u);
  EXPECT_EQ(ghosts.columns().size(), 2u) << "columns outlive the ghosts of a tick";
}

TEST(GhostStore, TheColumnsReadTheOwnersState) {
  EntityStore store;
  EntityRecordData npc;
  npc.id = EntityId{1};
  npc.kind = EntityKind::Npc;
  npc.npc.population = 4;
  npc.agent.type = 1;
  EntityRecordData body;
  body.id = EntityId{2};
  body.kind = EntityKind::RigidBody;
  store.add(npc);
  store.add(body);
  std::vector<std::int64_t> crowd, agent;
  crowdPopulationColumn().read(store, crowd);
  agentTypeColumn().read(store, agent);
  ASSERT_EQ(crowd.size(), 2u);
  ASSERT_EQ(agent.size(), 2u);
  EXPECT_EQ(crowd[0], 4);
  EXPECT_EQ(agent[0], 1);
  EXPECT_EQ(crowd[1], -1);
  EXPECT_EQ(agent[1], -1);
}

}  // namespace
}  // namespace zonesim::zone
