#pragma once
// Small scenes built in code for zone tests (no files needed), and the options to run them.

#include <gtest/gtest.h>

#include <string>

#include "common/scene.h"
#include "zone_node/zone_node.h"

namespace zonesim::testing {

/// A 200 m x 200 m world, 2x2 zones, 30 Hz, with the given NPC count and nothing else.
inline Scene npcScene(int npcs, std::uint64_t seed = 7) {
  Scene s;
  s.name = "npc_test";
  s.world = {{0, 0, 0}, {200, 50, 200}};
  s.dt = 1.0 / 30;
  s.seed = seed;
  s.zones.columns = 2;
  s.zones.rows = 2;
  s.interest_cell_size = 50;
  NpcPopulation p;
  p.count = npcs;
  p.min_speed = 1;
  p.max_speed = 3;
  p.waypoint_radius = 60;
  p.region = s.world;
  s.npcs.push_back(p);
  return s;
}

/// Options for a zone run inside a test: no DDS, the CPU path, conservation checked every
/// `check_every` ticks (0: never).
inline zone::ZoneOptions localZone(int check_every) {
  zone::ZoneOptions o;
  o.dds = false;
  o.check_every = check_every;
  o.gpu = "off";
  return o;
}

/// A small scene for error tests: a 1-zone world (lines 1-4), then `rest` (from line 5).
inline std::string withSmallWorld(const std::string& rest) {
  return "world: {min: [0, 0, 0], max: [100, 10, 100]}\ntick: {dt: 0.02}\nseed: 1\n"
         "zones: {columns: 1, rows: 1}\n" +
         rest;
}

/// Expects parsing `text` (as file "t.yaml") to fail with a message containing `expect`.
inline void expectSceneError(const std::string& text, const std::string& expect) {
  try {
    parseScene(text, "t.yaml");
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
  }
}

}  // namespace zonesim::testing
