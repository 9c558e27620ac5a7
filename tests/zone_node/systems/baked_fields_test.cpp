// Flow fields stored with the map (map.fields, crowd/flow_field_file.h): a crowd on fields
// read from a file ends bitwise where the same crowd on fields built at start ends, and a file
// built for another map, one that lacks a destination, or one that is not there is a scene
// error at map.fields that says which.

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/scene.h"
#include "crowd/flow_field.h"
#include "crowd/flow_field_file.h"
#include "zone_node/population.h"
#include "zone_node/systems/flow_movement.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/world_map.h"
#include "zone_node/zone_map.h"

namespace zonesim::zone {
namespace {

Scene courtyard() {
  return loadScene(std::string(ZONESIM_SOURCE_DIR) + "/scenes/courtyard_flow.yaml");
}

/// Bakes the fields of the scene's destinations (the first `count` of them) on `grid`.
void bake(const Scene& scene, const ai::GridMap& grid, const crowd::MapFrame& frame,
          const std::string& path, std::size_t count) {
  std::vector<std::unique_ptr<crowd::FlowField>> fields;
  std::vector<const crowd::FlowField*> views;
  const auto& destinations = scene.npcs[0].flow.destinations;
  for (std::size_t k = 0; k < count && k < destinations.size(); ++k) {
    fields.push_back(std::make_unique<crowd::FlowField>(
        grid, frame.cellOf({destinations[k].x, destinations[k].z})));
    views.push_back(fields.back().get());
  }
  crowd::writeFlowFields(path, grid, views);
}

std::vector<Vec3> run(const Scene& scene, int ticks) {
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  FlowMovement flows(scene, map.get());
  LoneZone lone{scene.dt};
  for (int t = 0; t < ticks; ++t) lone.step(flows, store, std::uint64_t(t));
  return std::vector<Vec3>(store.pos.begin(), store.pos.end());
}

std::string sceneErrorOf(const Scene& scene) {
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  try {
    FlowMovement flows(scene, map.get());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

class BakedFields : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("zs_baked_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string file(const char* name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(BakedFields, ACrowdOnLoadedFieldsEndsBitwiseWhereItEndsOnBuiltOnes) {
  const Scene built = courtyard();
  std::unique_ptr<ZoneMap> map = ZoneMap::load(built);
  bake(built, map->world().grid, map->world().frame, file("all.fields"), 3);
  Scene loaded = built;
  loaded.map.fields = file("all.fields");
  const std::vector<Vec3> a = run(built, 400), b = run(loaded, 400);
  ASSERT_EQ(a.size(), 400u);
  EXPECT_EQ(a, b);
}

TEST_F(BakedFields, WrongMissingOrAbsentFieldsAreSceneErrorsThatSayWhich) {
  Scene scene = courtyard();
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  // Built for the courtyard with one more wall cell: another map.
  ai::GridMap other = map->world().grid;
  for (int x = 0; x < other.width(); ++x)
    if (other.passable(x, 1)) {
      other.setPassable(x, 1, false);
      break;
    }
  bake(scene, other, map->world().frame, file("other.fields"), 3);
  scene.map.fields = file("other.fields");
  EXPECT_NE(
      sceneErrorOf(scene).find("map.fields: " + file("other.fields") + ": built for another map"),
      std::string::npos)
      << sceneErrorOf(scene);
  // Two of the three destinations only.
  bake(scene, map->world().grid, map->world().frame, file("two.fields"), 2);
  scene.map.fields = file("two.fields");
  EXPECT_NE(sceneErrorOf(scene).find("has no field for populations[0].flow.destinations[2]"),
            std::string::npos)
      << sceneErrorOf(scene);
  scene.map.fields = file("absent.fields");
  EXPECT_NE(sceneErrorOf(scene).find("cannot open flow fields file"), std::string::npos)
      << sceneErrorOf(scene);
  // Not a fields file at all: the map itself.
  scene.map.fields = scene.map.file;
  EXPECT_NE(sceneErrorOf(scene).find("not a flow fields file"), std::string::npos)
      << sceneErrorOf(scene);
}

}  // namespace
}  // namespace zonesim::zone
