// The duel scene loads, its duels adapt their NPCs in a zone, the same on every run, and the
// scene's bad adaptation settings and model files are refused with errors that say where.

#include "zone_node/systems/duels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "ai/parse_error.h"
#include "common/scene.h"
#include "zone_node/entity_store.h"
#include "zone_node/systems/lone_zone.h"

namespace zonesim::zone {
namespace {

const std::string kScene = ZONESIM_SOURCE_DIR "/scenes/duel_adaptive.yaml";

std::vector<DuelFigures> run(const Scene& scene, int ticks) {
  DuelSystem duels(scene.adaptation, scene.seed, [](double, double) { return true; });
  EntityStore store;
  LoneZone zone(scene.dt);
  for (int t = 0; t < ticks; ++t) zone.step(duels, store, std::uint64_t(t));
  return duels.figures();
}

TEST(DuelScene, LoadsWithItsSettings) {
  const Scene scene = loadScene(kScene);
  const AdaptationSettings& a = scene.adaptation;
  EXPECT_TRUE(a.enabled);
  EXPECT_EQ(a.mode, AdaptationSettings::Mode::Model);
  EXPECT_EQ(a.model, std::string(ZONESIM_SOURCE_DIR "/scenes/ai/duel_model.txt"));
  EXPECT_EQ(a.target_win_rate, 0.5);
  ASSERT_EQ(a.duels.size(), 10u);
  EXPECT_EQ(a.duels.front().skill, 0.1);
  EXPECT_EQ(a.duels.back().skill, 0.9);
}

TEST(DuelScene, ScenesWithoutTheKeyRunNoDuels) {
  const Scene scene = loadScene(ZONESIM_SOURCE_DIR "/scenes/test_npc_only.yaml");
  EXPECT_FALSE(scene.adaptation.enabled);
  DuelSystem duels(scene.adaptation, scene.seed, [](double, double) { return true; });
  EXPECT_FALSE(duels.active());
  EXPECT_TRUE(duels.figures().empty());
}

// Every duel plays rounds, its NPC stays in range, and two runs end identically.
TEST(DuelScene, DuelsAdaptAndRepeat) {
  const Scene scene = loadScene(kScene);
  const std::vector<DuelFigures> a = run(scene, 2000), b = run(scene, 2000);
  ASSERT_EQ(a.size(), 10u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_GT(a[i].rounds, 100u) << i;
    EXPECT_EQ(a[i].rounds, b[i].rounds);
    EXPECT_EQ(a[i].player_wins, b[i].player_wins);
    EXPECT_EQ(a[i].npc.accuracy, b[i].npc.accuracy);
    EXPECT_EQ(a[i].guard.fallbacks, 0u);
  }
  // The model makes the NPC facing the strongest player harder than the weakest one's.
  EXPECT_GT(a.back().npc.accuracy, a.front().npc.accuracy);
}

// Only the duels whose arena the zone holds run there.
TEST(DuelScene, AZoneRunsOnlyItsArenas) {
  const Scene scene = loadScene(kScene);
  DuelSystem duels(scene.adaptation, scene.seed, [](double x, double) { return x < 50; });
  const std::vector<DuelFigures> mine = duels.figures();
  ASSERT_EQ(mine.size(), 4u);  // skills 0.1 and 0.5, two duels each
  EXPECT_EQ(mine[0].index, 0u);
  EXPECT_EQ(mine[3].index, 5u);
}

TEST(DuelScene, BadModelFileNamesItsLine) {
  const std::string path = ::testing::TempDir() + "/bad_duel_model.txt";
  std::ofstream(path) << "zonesim-adapt-model 1\nbasis cubic-hd\nweights 1 2 3\n";
  Scene scene = loadScene(kScene);
  scene.adaptation.model = path;
  try {
    DuelSystem duels(scene.adaptation, scene.seed, [](double, double) { return true; });
    ADD_FAILURE() << "a bad model file was accepted";
  } catch (const ai::ParseError& e) {
    EXPECT_EQ(std::string(e.what()), path + ":3: weights: expected 10 numbers, got 3");
  }
}

// Settings the scene-file cases (tests/data/scenes_bad/adaptation_*.yaml) do not cover: the
// message names the key.
TEST(DuelScene, BadSettingsNameTheKey) {
  const std::string base =
      "world: {min: [0, 0, 0], max: [100, 10, 100]}\ntick: {dt: 0.05}\nseed: 1\n"
      "zones: {columns: 1, rows: 1}\nadaptation:\n";
  auto error = [&](const std::string& tail) {
    try {
      parseScene(base + tail, "inline.yaml");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error("  model: no_such_model.txt\n  duels: [{skill: 0.5, at: [1, 1]}]\n"),
            "inline.yaml:6: adaptation.model: cannot open model file 'no_such_model.txt'");
  EXPECT_EQ(error("  mode: off\n  duels: []\n"),
            "inline.yaml:7: adaptation.duels: needs at least one duel");
  EXPECT_EQ(error("  mode: off\n  duels: [{skill: 0.5, at: [300, 1]}]\n"),
            "inline.yaml:7: adaptation.duels[0].at: (300, 1) is outside the world");
  EXPECT_EQ(error("  mode: off\n  max_step: 0\n  duels: [{skill: 0.5, at: [1, 1]}]\n"),
            "inline.yaml:7: adaptation.max_step: must be in (0, 1], got 0");
  EXPECT_EQ(error("  mode: off\n  gain: 3\n  duels: [{skill: 0.5, at: [1, 1]}]\n"),
            "inline.yaml:7: adaptation.gain: unknown key (allowed: enabled, mode, model, "
            "target_win_rate, max_step, rubber_band, duels)");
}

}  // namespace
}  // namespace zonesim::zone
