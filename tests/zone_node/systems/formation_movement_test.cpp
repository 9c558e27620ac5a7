// Formations in a zone (zone_node/systems/formation_movement.h) on the courtyard map: members
// hold their slots while the centre crosses open ground; a member standing behind a wall plans
// A* round it and takes its slot again; the shipped scene's group follows its whole route
// through pillars and doors and ends in formation; route points on walls are scene errors.

#include "zone_node/systems/formation_movement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "ai/grid_search.h"
#include "common/scene.h"
#include "crowd/formation.h"
#include "crowd/map_frame.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/world_map.h"

namespace zonesim::zone {
namespace {

std::string source(const std::string& relative) {
  return std::string(ZONESIM_SOURCE_DIR) + "/" + relative;
}

struct FormationRun {
  double worst_moving = 0;  // worst slot error of a member in formation while the centre moves
  int on_walls = 0;         // member-ticks on a blocked cell
  int ticks = 0;
  std::size_t updates = 0;  // member steps taken
};

// Steps the formation until its centre has arrived and every member stands within `settle` of
// its slot in formation, or `max_ticks`.
FormationRun runFormation(const Scene& scene, const WorldMap& map, EntityStore& store,
                          FormationMovement& f, int max_ticks, double settle,
                          std::vector<crowd::Vec2> players = {}) {
  FormationRun r;
  LoneZone lone{scene.dt};
  lone.players = std::move(players);
  for (; r.ticks < max_ticks; ++r.ticks) {
    lone.step(f, store, std::uint64_t(r.ticks));
    r.updates += f.updates();
    bool settled = f.centre(0).arrived();
    for (std::size_t i = 0; i < store.size(); ++i) {
      crowd::Vec2 p{store.pos[i].x(), store.pos[i].z()};
      double err = crowd::length(p - f.slotPosition(store, i));
      bool in = std::get<FormationMemberData>(store.npc[i].crowd).mode ==
                int(crowd::MemberMode::InFormation);
      if (!f.centre(0).arrived() && in) r.worst_moving = std::max(r.worst_moving, err);
      settled = settled && in && err < settle;
      r.on_walls += map.walkable(p.x, p.y) ? 0 : 1;
    }
    if (settled) break;
  }
  return r;
}

TEST(FormationMovement, MembersHoldTheirSlotsAcrossOpenGround) {
  // The east yard is open: nobody is ever cut off, and the slots are held while moving.
  Scene scene = loadScene(source("scenes/courtyard_formation.yaml"));
  NpcFormation& f = scene.npcs[0].formation;
  f.route = {{26.5, 4.5, 0}, {58.5, 26.5, 0}};
  f.turn_rate = 1.0;  // the outer slots of a wide block swing fast when the heading turns
  auto map = loadWorldMap(scene);
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  ASSERT_EQ(store.size(), 12u);
  FormationMovement move(scene, map.get());
  FormationRun r = runFormation(scene, *map, store, move, 4000, 0.1);
  std::printf("settled after %.1f s; worst slot error while moving %.3f m; %d rejoin plans\n",
              r.ticks * scene.dt, r.worst_moving, move.rejoinPlans());
  EXPECT_TRUE(move.centre(0).arrived());
  EXPECT_LT(r.ticks, 4000);          // every member ends within 0.1 m of its slot
  EXPECT_LT(r.worst_moving, 1.0);    // the stated tolerance while the centre moves
  EXPECT_EQ(move.rejoinPlans(), 0);  // open ground: nobody is cut off
  EXPECT_EQ(r.on_walls, 0);
}

TEST(FormationMovement, AMemberBehindAWallPlansAStarBackAndRejoins) {
  // The group waits in the west hall; member 0 starts in the east yard behind the hall's wall
  // (x = 22): no line of sight, so it plans A* through the north door and takes its slot.
  Scene scene = loadScene(source("scenes/courtyard_formation.yaml"));
  NpcFormation& f = scene.npcs[0].formation;
  f.route = {{12.5, 25.5, 0}, {12.5, 26.5, 0}};
  auto map = loadWorldMap(scene);
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  const crowd::Vec2 start{30.5, 25.5};
  store.pos[0] = Vec3(start.x, 0, start.y);
  FormationMovement move(scene, map.get());
  ai::GridSearch search(map->grid);
  ai::GridPath around;
  ASSERT_TRUE(search.findPath(map->frame.cellOf(start), map->frame.cellOf({12.5, 26.5}), around));
  // Stated bound: the A* way round at the members' top speed, doubled.
  const double bound = 2 * around.length / f.max_speed;
  bool cut_off = false;
  int ticks = 0;
  for (; ticks < int(bound / scene.dt); ++ticks) {
    LoneZone{scene.dt}.step(move, store, std::uint64_t(ticks));
    cut_off = cut_off || std::get<FormationMemberData>(store.npc[0].crowd).mode ==
                             int(crowd::MemberMode::Rejoining);
    ASSERT_TRUE(map->walkable(store.pos[0].x(), store.pos[0].z())) << ticks;
    crowd::Vec2 p{store.pos[0].x(), store.pos[0].z()};
    if (std::get<FormationMemberData>(store.npc[0].crowd).mode ==
            int(crowd::MemberMode::InFormation) &&
        crowd::length(p - move.slotPosition(store, 0)) < 0.1)
      break;
  }
  std::printf("rejoined after %.1f s (bound %.1f s, A* round the wall %.1f m), %d plans\n",
              ticks * scene.dt, bound, around.length, move.rejoinPlans());
  EXPECT_TRUE(cut_off);
  EXPECT_GE(move.rejoinPlans(), 1);
  EXPECT_LT(ticks, int(bound / scene.dt));
}

TEST(FormationMovement, TheCourtyardGroupFollowsItsRouteAndEndsInFormation) {
  // The shipped scene: pillars and door posts cut members off on the way; all rejoin.
  Scene scene = loadScene(source("scenes/courtyard_formation.yaml"));
  auto map = loadWorldMap(scene);
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  FormationMovement move(scene, map.get());
  FormationRun r = runFormation(scene, *map, store, move, 6000, 0.25);
  const ScenePoint& end = scene.npcs[0].formation.route.back();
  std::printf("settled after %.1f s, %d rejoin plans on the way\n", r.ticks * scene.dt,
              move.rejoinPlans());
  EXPECT_LT(r.ticks, 6000);
  EXPECT_EQ(r.on_walls, 0);
  EXPECT_LT(crowd::length(move.centre(0).position() - crowd::Vec2{end.x, end.z}), 1e-9);
}

double routeLength(const std::vector<crowd::Vec2>& route) {
  double sum = 0;
  for (std::size_t k = 1; k < route.size(); ++k) sum += crowd::length(route[k] - route[k - 1]);
  return sum;
}

TEST(FormationMovement, OnTheNavMeshTheCentreWalksStraightClearOfWallsAndTheGroupEndsInFormation) {
  // The same group with map.navigation: navmesh and map.agent_radius 1 m: the centre's route
  // runs from corner to corner of the funnelled mesh path, every leg in sight and every corner
  // at least 1 m from a wall, and is shorter than the grid route's cell centres.
  Scene grid_scene = loadScene(source("scenes/courtyard_formation.yaml"));
  Scene scene = loadScene(source("scenes/courtyard_formation_navmesh.yaml"));
  auto map = loadWorldMap(scene);
  FormationMovement on_grid(grid_scene, map.get());
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  FormationMovement move(scene, map.get());
  const std::vector<crowd::Vec2>& route = move.centre(0).route();
  int blind = 0, near_walls = 0;
  for (std::size_t k = 1; k < route.size(); ++k)
    blind += !crowd::lineOfSight(map->grid, map->frame, route[k - 1], route[k]);
  for (const crowd::Vec2 p : route) {
    for (int y = 0; y < map->grid.height(); ++y)
      for (int x = 0; x < map->grid.width(); ++x) {
        if (map->grid.passable(x, y)) continue;
        const double dx = std::max({x - p.x, 0.0, p.x - (x + 1)});
        const double dy = std::max({y - p.y, 0.0, p.y - (y + 1)});
        near_walls += std::hypot(dx, dy) < 1.0 - 1e-9;
      }
  }
  const double grid_length = routeLength(on_grid.centre(0).route()), length = routeLength(route);
  const FormationRun grid_run = [&] {
    EntityStore grid_store;
    forEachInitialEntity(grid_scene, [&](const EntityRecordData& r) { grid_store.add(r); });
    return runFormation(grid_scene, *map, grid_store, on_grid, 6000, 0.25);
  }();
  const FormationRun r = runFormation(scene, *map, store, move, 6000, 0.25);
  std::printf(
      "route: grid %zu points %.2f m, navmesh %zu points %.2f m; settled after %.1f s "
      "(grid %.1f s), %d rejoin plans; worst slot error while moving %.2f m (grid %.2f m)\n",
      on_grid.centre(0).route().size(), grid_length, route.size(), length, r.ticks * scene.dt,
      grid_run.ticks * scene.dt, move.rejoinPlans(), r.worst_moving, grid_run.worst_moving);
  EXPECT_EQ(blind, 0);
  EXPECT_EQ(near_walls, 0);
  EXPECT_LT(length, grid_length);
  EXPECT_LT(r.ticks, 6000);
  EXPECT_EQ(r.on_walls, 0);
  const ScenePoint& end = scene.npcs[0].formation.route.back();
  EXPECT_LT(crowd::length(move.centre(0).position() - crowd::Vec2{end.x, end.z}), 1e-9);
}

TEST(FormationMovement, UnderLodFarMembersStepLessOftenAndTheGroupStillEndsInFormation) {
  // An observer at the start of the route: the group leaves full detail (6 m) through the
  // middle band (every 2 ticks, to 15 m) into the far band (every 4 ticks, no separation).
  Scene scene = loadScene(source("scenes/courtyard_formation.yaml"));
  scene.lod.enabled = true;
  scene.lod.near_radius = 6;
  scene.lod.far_radius = 15;
  scene.lod.mid_every = 2;
  scene.lod.far_every = 4;
  const std::vector<crowd::Vec2> observer{{16.5, 24.5}};
  auto map = loadWorldMap(scene);
  auto runWith = [&](const Scene& s, EntityStore& store, FormationRun& r) {
    forEachInitialEntity(s, [&](const EntityRecordData& e) { store.add(e); });
    FormationMovement move(s, map.get());
    r = runFormation(s, *map, store, move, 6000, 0.25, observer);
    return move.centre(0).arrived();
  };
  Scene full = scene;
  full.lod.enabled = false;
  EntityStore full_store, lod_store;
  FormationRun full_run, lod_run;
  ASSERT_TRUE(runWith(full, full_store, full_run));
  ASSERT_TRUE(runWith(scene, lod_store, lod_run));
  const double ratio = double(lod_run.updates) / double(12 * lod_run.ticks);
  std::printf(
      "full detail settled after %.1f s, with LOD after %.1f s; member steps %.2f of every "
      "tick's\n",
      full_run.ticks * scene.dt, lod_run.ticks * scene.dt, ratio);
  EXPECT_LT(lod_run.ticks, 6000);  // every member ends within 0.25 m of its slot
  EXPECT_EQ(lod_run.on_walls, 0);
  EXPECT_LT(ratio, 0.5);
  EXPECT_NEAR(lod_run.ticks * scene.dt, full_run.ticks * scene.dt, 5.0);

  // Everyone within the near band: exactly the full-detail run.
  Scene all_near = scene;
  all_near.lod.near_radius = 1000;
  all_near.lod.far_radius = 1000;
  EntityStore near_store;
  FormationRun near_run;
  ASSERT_TRUE(runWith(all_near, near_store, near_run));
  ASSERT_EQ(near_run.ticks, full_run.ticks);
  for (std::size_t i = 0; i < full_store.size(); ++i) {
    EXPECT_EQ(near_store.pos[i], full_store.pos[i]) << i;
  }
}

TEST(FormationMovement, ARoutePointOnAWallIsASceneError) {
  Scene scene = loadScene(source("scenes/courtyard_formation.yaml"));
  scene.npcs[0].formation.route[2] = {22.5, 20.5, 33};  // column 22 is a wall at row 20
  auto map = loadWorldMap(scene);
  try {
    FormationMovement move(scene, map.get());
    ADD_FAILURE() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              scene.source_path +
                  ":33: populations[0].formation.route[2]: lies on a blocked cell of the map");
  }
}

}  // namespace
}  // namespace zonesim::zone
