#pragma once
// The scene's `adaptation` key in a zone: each duel is a simulated player of a given skill
// against an NPC that adapts to it (ai/adapt/). One exchange of blows per tick; after each
// round the NPC adapts (model, rubber band or not at all), through the guards.
// A duel is run by the zone that held its arena at the start, for the whole run: it is not an
// entity and never migrates, so its result is the same on any number of ranks. Its random
// stream comes from the scene seed and its index alone.

#include <cstdint>
#include <memory>
#include <vector>

#include "ai/adapt/adapter.h"
#include "common/rng.h"
#include "common/scene_adaptation.h"
#include "zone_node/systems/step_context.h"

namespace zonesim::zone {

/// One duel's figures so far.
struct DuelFigures {
  std::size_t index = 0;  ///< in the scene's list
  double skill = 0;
  std::uint64_t rounds = 0;
  std::uint64_t player_wins = 0;
  ai::adapt::NpcParams npc;  ///< the NPC the next round meets
  ai::adapt::GuardStats guard;
};

/// Runs the duels whose arenas this zone held at the start.
class DuelSystem : public ZoneSystem {
 public:
  /// `owned(x, z)`: whether this zone holds the point. Loads the model file (its errors name
  /// the file and line) when the scene's mode needs it.
  template <typename Owned>
  DuelSystem(const AdaptationSettings& settings, std::uint64_t seed, Owned owned)
      : DuelSystem(settings) {
    for (std::size_t i = 0; i < settings.duels.size(); ++i)
      if (settings.enabled && owned(settings.duels[i].x, settings.duels[i].z)) add(i, seed);
  }
  ~DuelSystem() override;

  bool active() const override { return enabled_; }
  /// One exchange in every duel; rounds that end adapt their NPC.
  void step(StepContext& ctx) override;
  /// This zone's duels, in scene order.
  std::vector<DuelFigures> figures() const;

 private:
  struct Duel {
    DuelFigures figures;
    double accuracy;  // the player's
    Pcg32 rng;
    ai::adapt::DuelAdapter adapter;
    ai::adapt::DuelRound round;
  };
  explicit DuelSystem(const AdaptationSettings& settings);
  void add(std::size_t index, std::uint64_t seed);

  bool enabled_;
  AdaptationSettings settings_;
  ai::adapt::AdaptSettings adapt_;
  std::unique_ptr<ai::adapt::DuelModel> model_;
  std::vector<Duel> duels_;
};

}  // namespace zonesim::zone
