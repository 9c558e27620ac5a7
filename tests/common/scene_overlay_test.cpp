// Overlay scene files (common/scene_loader_overlay.h): what the tuner writes, read back as the
// base scene with only the named values changed; errors in them name the overlay's own lines.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/scene.h"
#include "scene_test_util.h"

namespace zonesim {
namespace {

using test::sceneError;
using test::sourcePath;

class SceneOverlay : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (std::filesystem::temp_directory_path() / "zonesim-overlay-XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  std::filesystem::path dir_;
};

TEST_F(SceneOverlay, ChangesOnlyTheValuesItNames) {
  const std::string base = sourcePath("scenes/demo.yaml");
  std::string overlay = write("tuned.yaml", "overlay_of: " + base + R"(
dead_reckoning:
  position_threshold: 0.35
  quantisation:
    rotation_bits: 8
)");
  Scene plain = loadScene(base);
  Scene tuned = loadScene(overlay);
  EXPECT_EQ(tuned.name, "demo");  // the base's scene, changed
  EXPECT_EQ(tuned.source_path, overlay);
  EXPECT_EQ(tuned.dead_reckoning.position_threshold, 0.35);
  EXPECT_EQ(tuned.dead_reckoning.quantisation.rotation_bits, 8);
  // Keys beside them in the same mappings keep the base's values.
  EXPECT_EQ(tuned.dead_reckoning.heartbeat_seconds, plain.dead_reckoning.heartbeat_seconds);
  EXPECT_EQ(tuned.dead_reckoning.quantisation.position_resolution,
            plain.dead_reckoning.quantisation.position_resolution);
  EXPECT_EQ(tuned.seed, plain.seed);
  EXPECT_EQ(tuned.dt, plain.dt);
  EXPECT_EQ(tuned.npcs.size(), plain.npcs.size());
  EXPECT_EQ(tuned.zones.columns, plain.zones.columns);
  EXPECT_EQ(tuned.interest_cell_size, plain.interest_cell_size);
}

TEST_F(SceneOverlay, WrittenValuesReadBackExactly) {
  // What bench/tune.py writes: full-precision numbers and choices, read back unchanged.
  std::string overlay = write("roundtrip.yaml", "overlay_of: " + sourcePath("scenes/demo.yaml") + R"(
dead_reckoning:
  position_threshold: 0.1234567890123
  models:
    npc: {order: second}
    avatar: {order: first}
  quantisation:
    position_resolution: 0.0078125
)");
  Scene s = loadScene(overlay);
  EXPECT_EQ(s.dead_reckoning.position_threshold, 0.1234567890123);
  EXPECT_EQ(s.dead_reckoning.quantisation.position_resolution, 0.0078125);
  EXPECT_EQ(s.dead_reckoning.npc.order, DeadReckoningModel::Order::Second);
  EXPECT_EQ(s.dead_reckoning.avatar.order, DeadReckoningModel::Order::First);
}

TEST_F(SceneOverlay, AnOverlayOfAnOverlayAppliesBothInOrder) {
  std::string first = write("first.yaml", "overlay_of: " + sourcePath("scenes/demo.yaml") +
                                              "\ndead_reckoning: {position_threshold: 0.3, heartbeat_s: 2}\n");
  std::string second = write("second.yaml", "overlay_of: first.yaml\ndead_reckoning: {position_threshold: 0.2}\n");
  Scene s = loadScene(second);
  EXPECT_EQ(s.dead_reckoning.position_threshold, 0.2);
  EXPECT_EQ(s.dead_reckoning.heartbeat_seconds, 2.0);
}

TEST_F(SceneOverlay, TheBasesRelativePathsStayTheBases) {
  // courtyard_flow.yaml names maps/courtyard.map beside itself; the overlay lives elsewhere.
  std::string overlay = write("flow.yaml", "overlay_of: " + sourcePath("scenes/courtyard_flow.yaml") +
                                               "\nseed: 99\n");
  Scene s = loadScene(overlay);
  EXPECT_EQ(s.seed, 99u);
  EXPECT_EQ(std::filesystem::path(s.map.file).lexically_normal(),
            std::filesystem::path(sourcePath("scenes/maps/courtyard.map")).lexically_normal());
}

TEST_F(SceneOverlay, AnErrorInAnOverlayNamesTheOverlaysLine) {
  std::string overlay = write("bad.yaml", "overlay_of: " + sourcePath("scenes/demo.yaml") + R"(
dead_reckoning:
  position_threshold: -1
)");
  EXPECT_EQ(sceneError([&] { loadScene(overlay); }),
            overlay + ":3: dead_reckoning.position_threshold: must be >= 0, got -1");
  std::string unknown = write("unknown.yaml", "overlay_of: " + sourcePath("scenes/demo.yaml") +
                                                  "\n\ndead_reckonin: {position_threshold: 1}\n");
  EXPECT_NE(sceneError([&] { loadScene(unknown); }).find(unknown + ":3: dead_reckonin: unknown key"),
            std::string::npos)
      << sceneError([&] { loadScene(unknown); });
}

TEST_F(SceneOverlay, ABaseThatCannotBeReadOrLoopsIsNamed) {
  std::string missing = write("missing.yaml", "overlay_of: nowhere.yaml\nseed: 1\n");
  EXPECT_EQ(sceneError([&] { loadScene(missing); }),
            missing + ":1: overlay_of: cannot open base scene '" + (dir_ / "nowhere.yaml").string() + "'");
  write("a.yaml", "overlay_of: b.yaml\n");
  std::string b = write("b.yaml", "overlay_of: a.yaml\n");
  EXPECT_NE(sceneError([&] { loadScene(b); }).find("is already in this chain of overlays"),
            std::string::npos);
  std::string listed = write("listed.yaml", "overlay_of: [demo.yaml]\n");
  EXPECT_EQ(sceneError([&] { loadScene(listed); }),
            listed + ":1: overlay_of: expected the path of the scene this file changes");
}

TEST(ShippedOverlays, TheTunedScenesLoadAsTheScenesTheyChange) {
  std::vector<std::string> tuned = test::yamlStems("scenes/tuned");
  ASSERT_FALSE(tuned.empty());
  for (const std::string& stem : tuned) {
    Scene s = loadScene(sourcePath("scenes/tuned/" + stem + ".yaml"));
    EXPECT_EQ(s.name + ".tuned", stem);
    // Something to simulate: NPCs, bodies (the stacks the physics limit is tuned on), or
    // agents (the couriers the path limit is tuned on).
    EXPECT_TRUE(!s.npcs.empty() || !s.rigid_bodies.empty() || !s.physics.bodies.empty() ||
                !s.agents.populations.empty())
        << stem;
  }
}

}  // namespace
}  // namespace zonesim
