#pragma once
// Training on simulated play: players of many skills duel NPCs of random difficulty (so the
// data covers every pairing the adapter may ask about), each round recorded as (the player's
// measured hit rate before it, the NPC's difficulty, who won); a logistic regression on the
// cubic basis is then fitted by Newton's method (iteratively reweighted least squares).

#include <cstdint>
#include <vector>

#include "ai/adapt/duel_model.h"

namespace zonesim::ai::adapt {

/// A training run.
struct TrainOptions {
  std::uint64_t seed = 7;
  int players = 64;             ///< simulated players, skills spread evenly over [0, 1]
  int rounds_per_player = 500;  ///< rounds each plays
  double smoothing = 0.05;      ///< of the hit-rate measure (PlayerFeatures); the model keeps it
  int newton_iterations = 25;   ///< at most; stops earlier once the step is tiny
  double ridge = 1e-6;          ///< keeps the Newton system invertible on separable data
};

/// One recorded round.
struct Sample {
  double hit_rate;
  double difficulty;
  bool player_won;
};

/// Plays the training rounds.
std::vector<Sample> simulatePlay(const TrainOptions& options);

/// How the fit went.
struct FitReport {
  int iterations = 0;
  double log_loss = 0;  ///< mean negative log-likelihood per sample at the end
};

/// Fits the model to the samples.
DuelModel fitModel(const std::vector<Sample>& samples, const TrainOptions& options,
                   FitReport* report = nullptr);

/// simulatePlay then fitModel.
DuelModel train(const TrainOptions& options, FitReport* report = nullptr);

}  // namespace zonesim::ai::adapt
