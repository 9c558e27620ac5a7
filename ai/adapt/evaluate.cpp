#include "ai/adapt/evaluate.h"

#include "common/rng.h"

namespace zonesim::ai::adapt {

std::vector<SkillOutcome> evaluate(const std::vector<double>& skills, const AdaptSettings& settings,
                                   const DuelModel* model, const EvalOptions& o) {
  std::vector<SkillOutcome> out;
  for (std::size_t s = 0; s < skills.size(); ++s) {
    SkillOutcome outcome;
    outcome.skill = skills[s];
    for (int p = 0; p < o.players_per_skill; ++p) {
      // One stream per (skill, player): each player's rounds are the same whatever the mode.
      Pcg32 rng(o.seed, s * 65536 + std::uint64_t(p));
      DuelAdapter adapter(settings, model);
      for (int r = 0; r < o.rounds_per_player; ++r) {
        const RoundResult result = playRound(rng, playerAccuracy(skills[s]), adapter.params());
        adapter.onRound(result);
        ++outcome.rounds;
        outcome.player_wins += result.player_won ? 1 : 0;
      }
      outcome.fallbacks += adapter.guardStats().fallbacks;
    }
    out.push_back(outcome);
  }
  return out;
}

}  // namespace zonesim::ai::adapt
