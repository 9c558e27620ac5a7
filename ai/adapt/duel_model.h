#pragma once
// The learned model: P(player wins a round | measured hit rate h, NPC difficulty d), a
// logistic regression on a cubic polynomial of (h, d). Adapting inverts it: the difficulty
// at which this player is predicted to win the target share of rounds.

#include <array>
#include <cstddef>
#include <cstdint>

namespace zonesim::ai::adapt {

/// Terms of the cubic basis in (h, d): 1, u, v, u², uv, v², u³, u²v, uv², v³.
constexpr std::size_t kBasisSize = 10;
/// A feature vector.
using Basis = std::array<double, kBasisSize>;

/// The basis at hit rate `h` and difficulty `d` (both centred to [-1, 1] first).
Basis basisAt(double h, double d);

/// A trained model and where it came from.
struct DuelModel {
  Basis weights{};
  std::uint64_t trained_rounds = 0;  ///< samples it was fitted on
  std::uint64_t seed = 0;            ///< of the training run
  /// The hit-rate measure it was trained on (PlayerFeatures smoothing): an adapter measures
  /// its player the same way, or the model would read another quantity than it learned.
  double smoothing = 0.05;

  /// Predicted chance that a player of measured hit rate h beats an NPC of difficulty d; NaN
  /// when the logit is not finite.
  double winProbability(double h, double d) const;
  /// The difficulty in [0, 1] at which the prediction equals `target` (the nearer end of
  /// [0, 1] when none does); NaN when the model's output is not finite.
  double difficultyFor(double h, double target) const;
};

}  // namespace zonesim::ai::adapt
