// adapt_bench: what adaptive duel NPCs (ai/adapt/, zone_node/systems/duels.h) cost.
// 1. One adaptation step alone (measure the round, ask the model or the rubber band, guards),
//    in ns, for each mode.
// 2. DuelSystem::step for N duels, as a zone runs them: ns per NPC per tick, which includes an
//    exchange of blows every tick and an adaptation step whenever a round ends.
//
//   build/bin/adapt_bench [--ticks T] [--sizes 100,10000]

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "ai/adapt/adapter.h"
#include "ai/adapt/model_file.h"
#include "bench/bench_args.h"
#include "common/scene.h"
#include "zone_node/entity_store.h"
#include "zone_node/systems/duels.h"
#include "zone_node/systems/lone_zone.h"

using namespace zonesim;
using namespace zonesim::zone;
using Clock = std::chrono::steady_clock;

namespace {

const char* const kModes[] = {"model", "rubber_band", "off"};
const std::string kModel = ZONESIM_SOURCE_DIR "/scenes/ai/duel_model.txt";

double nsSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
}

void adaptationStep() {
  const ai::adapt::DuelModel model = ai::adapt::loadModel(kModel);
  const ai::adapt::AdaptMode modes[] = {
      ai::adapt::AdaptMode::Model, ai::adapt::AdaptMode::RubberBand, ai::adapt::AdaptMode::Off};
  constexpr int kSteps = 1000000;
  std::printf("adaptation step alone (%d steps)\nmode,ns_per_step\n", kSteps);
  for (int m = 0; m < 3; ++m) {
    ai::adapt::AdaptSettings s;
    s.mode = modes[m];
    ai::adapt::DuelAdapter a(s, &model);
    double sink = 0;
    const auto t0 = Clock::now();
    for (int i = 0; i < kSteps; ++i) {
      // Varying results, so the measure and the model's answer change every step.
      a.onRound({i % 3 == 0, 8 + i % 5, 3 + i % 4, 2});
      sink += a.params().accuracy;
    }
    std::printf("%s,%.1f\n", kModes[m], nsSince(t0) / kSteps);
    if (sink < 0) std::puts("");  // keeps the loop's work observable
  }
}

Scene duelScene(const char* mode, int duels) {
  const std::string text =
      std::string("world: {min: [0, 0, 0], max: [100, 10, 100]}\n") +
      "tick: {dt: 0.05}\nseed: 5\nzones: {columns: 1, rows: 1}\n" + "adaptation:\n  mode: " + mode +
      "\n  model: " + kModel +
      "\n  duels:\n    - {skill: 0.3, at: [20, 20], count: " + std::to_string(duels / 2) +
      "}\n    - {skill: 0.8, at: [60, 60], count: " + std::to_string(duels - duels / 2) + "}\n";
  return parseScene(text, "adapt_bench.yaml");
}

void perNpcPerTick(const std::vector<int>& sizes, int ticks) {
  std::printf("\nDuelSystem::step, %d ticks\nmode,npcs,ns_per_npc_per_tick,rounds_per_npc\n",
              ticks);
  for (const char* mode : kModes)
    for (int n : sizes) {
      const Scene scene = duelScene(mode, n);
      DuelSystem duels(scene.adaptation, scene.seed, [](double, double) { return true; });
      EntityStore store;
      LoneZone zone(scene.dt);
      const auto t0 = Clock::now();
      for (int t = 0; t < ticks; ++t) zone.step(duels, store, std::uint64_t(t));
      const double ns = nsSince(t0);
      std::uint64_t rounds = 0;
      for (const DuelFigures& f : duels.figures()) rounds += f.rounds;
      std::printf("%s,%d,%.1f,%.1f\n", mode, n, ns / (double(n) * ticks), double(rounds) / n);
    }
}

}  // namespace

int main(int argc, char** argv) {
  int ticks = 2000;
  std::vector<int> sizes{100, 10000};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--ticks") && i + 1 < argc) {
      ticks = bench::parseCounts("--ticks", argv[++i]).front();
    } else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
      sizes = bench::parseCounts("--sizes", argv[++i]);
    } else {
      std::fprintf(stderr, "usage: adapt_bench [--ticks T] [--sizes 100,10000]\n");
      return 2;
    }
  }
  adaptationStep();
  perNpcPerTick(sizes, ticks);
  return 0;
}
