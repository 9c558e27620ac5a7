// What a zone times at start-up under each --gpu mode (no timing here: only the choice of
// workloads). auto probes a flock large enough that the device could take it, and never the
// particles, whose measured default keeps a scene's sprays on one backend whatever the load;
// probe times both whenever the scene has either; on and off time nothing.

#include "zone_node/systems/offload_probe.h"

#include <gtest/gtest.h>

#include "common/scene.h"
#include "gpu/offload_probe.h"

namespace zonesim::zone {
namespace {

Scene sceneWith(int flockers, int emitters) {
  Scene scene;
  if (flockers > 0) {
    NpcPopulation flock;
    flock.count = flockers;
    flock.flock.enabled = true;
    scene.npcs.push_back(flock);
  }
  NpcPopulation walkers;  // walkers never offload, however many
  walkers.count = 50'000;
  scene.npcs.push_back(walkers);
  if (emitters > 0) {
    EmitterPopulation e;
    e.count = emitters;
    scene.emitters.push_back(e);
  }
  return scene;
}

TEST(OffloadProbe, AutoProbesOnlyAFlockTheDeviceCouldTake) {
  const int smallest = int(gpu::kProbeSizes[0]);
  const ProbedWorkloads large = probedWorkloads(sceneWith(smallest, 4), "auto");
  EXPECT_TRUE(large.flocks);
  EXPECT_FALSE(large.particles);
  EXPECT_FALSE(probedWorkloads(sceneWith(smallest - 1, 4), "auto").any());
  EXPECT_FALSE(probedWorkloads(sceneWith(0, 4), "auto").any());
}

TEST(OffloadProbe, ProbeTimesBothWorkloadsWhenTheSceneHasEither) {
  for (auto [flockers, emitters] : {std::pair{30, 0}, std::pair{0, 2}, std::pair{5'000, 2}}) {
    const ProbedWorkloads what = probedWorkloads(sceneWith(flockers, emitters), "probe");
    EXPECT_TRUE(what.flocks && what.particles) << flockers << " flockers, " << emitters;
  }
  EXPECT_FALSE(probedWorkloads(sceneWith(0, 0), "probe").any());
}

TEST(OffloadProbe, OnAndOffTimeNothing) {
  for (const char* mode : {"on", "off"})
    EXPECT_FALSE(probedWorkloads(sceneWith(64'000, 8), mode).any()) << mode;
}

}  // namespace
}  // namespace zonesim::zone
