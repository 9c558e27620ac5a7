#include "ai/adapt/learner.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "ai/adapt/duel.h"
#include "ai/adapt/features.h"
#include "common/rng.h"

namespace zonesim::ai::adapt {

namespace {
// Newton stops once no weight moves by more than this.
constexpr double kConverged = 1e-9;
}  // namespace

std::vector<Sample> simulatePlay(const TrainOptions& o) {
  std::vector<Sample> out;
  out.reserve(std::size_t(o.players) * std::size_t(o.rounds_per_player));
  for (int p = 0; p < o.players; ++p) {
    const double skill = (p + 0.5) / o.players;
    Pcg32 rng(o.seed, std::uint64_t(p));
    PlayerFeatures features(o.smoothing);
    for (int r = 0; r < o.rounds_per_player; ++r) {
      const double d = rng.uniform();  // explore: every difficulty, whatever the player
      const RoundResult result = playRound(rng, playerAccuracy(skill), paramsForDifficulty(d));
      // The adapter reads the measure before the round; the first round has none yet.
      if (features.rounds() > 0) out.push_back({features.hitRate(), d, result.player_won});
      features.observe(result);
    }
  }
  return out;
}

DuelModel fitModel(const std::vector<Sample>& samples, const TrainOptions& o, FitReport* report) {
  const Eigen::Index n = Eigen::Index(samples.size()), k = Eigen::Index(kBasisSize);
  Eigen::MatrixXd X(n, k);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Basis b = basisAt(samples[std::size_t(i)].hit_rate, samples[std::size_t(i)].difficulty);
    for (Eigen::Index j = 0; j < k; ++j) X(i, j) = b[std::size_t(j)];
    y(i) = samples[std::size_t(i)].player_won ? 1 : 0;
  }
  Eigen::VectorXd w = Eigen::VectorXd::Zero(k);
  int it = 0;
  for (; it < o.newton_iterations; ++it) {
    const Eigen::ArrayXd prob = 1.0 / (1.0 + (-(X * w)).array().exp());
    const Eigen::VectorXd grad = X.transpose() * (prob.matrix() - y) + o.ridge * w;
    const Eigen::ArrayXd weight = prob * (1 - prob);
    Eigen::MatrixXd H = X.transpose() * (X.array().colwise() * weight).matrix();
    H.diagonal().array() += o.ridge;
    const Eigen::VectorXd step = H.ldlt().solve(grad);
    w -= step;
    if (step.cwiseAbs().maxCoeff() < kConverged) {
      ++it;
      break;
    }
  }
  DuelModel model;
  for (Eigen::Index j = 0; j < k; ++j) model.weights[std::size_t(j)] = w(j);
  model.trained_rounds = samples.size();
  model.seed = o.seed;
  model.smoothing = o.smoothing;
  if (report) {
    report->iterations = it;
    double loss = 0;
    for (const Sample& s : samples) {
      const double q = model.winProbability(s.hit_rate, s.difficulty);
      loss -= std::log(std::max(1e-300, s.player_won ? q : 1 - q));
    }
    report->log_loss = samples.empty() ? 0 : loss / double(samples.size());
  }
  return model;
}

DuelModel train(const TrainOptions& options, FitReport* report) {
  return fitModel(simulatePlay(options), options, report);
}

}  // namespace zonesim::ai::adapt
