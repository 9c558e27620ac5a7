// adapt_train: trains the duel model on simulated play and writes the file a scene names
// (adaptation.model); then plays fresh players of five skills against NPCs adapted by the
// model, by rubber banding and not at all, and prints their win rates.

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "ai/adapt/evaluate.h"
#include "ai/adapt/learner.h"
#include "ai/adapt/model_file.h"
#include "common/cli.h"

using namespace zonesim::ai::adapt;

namespace {

void printTable(const DuelModel& model, const EvalOptions& eval, double target) {
  const std::vector<double> skills{0.1, 0.3, 0.5, 0.7, 0.9};
  std::printf("win rate by skill (%d players x %d rounds each, seed %llu, target %.2f +- 0.05)\n",
              eval.players_per_skill, eval.rounds_per_player, (unsigned long long)eval.seed,
              target);
  std::printf("%-12s", "mode");
  for (double s : skills) std::printf("  skill %.1f", s);
  std::printf("  in band\n");
  const std::pair<const char*, AdaptMode> modes[] = {
      {"model", AdaptMode::Model}, {"rubber_band", AdaptMode::RubberBand}, {"off", AdaptMode::Off}};
  for (auto [name, mode] : modes) {
    AdaptSettings settings;
    settings.mode = mode;
    settings.target_win_rate = target;
    std::vector<SkillOutcome> out = evaluate(skills, settings, &model, eval);
    int in_band = 0;
    std::printf("%-12s", name);
    for (const SkillOutcome& o : out) {
      std::printf("  %9.1f%%", 100 * o.winRate());
      in_band += std::abs(o.winRate() - target) <= 0.05 ? 1 : 0;
    }
    std::printf("  %d of %zu\n", in_band, out.size());
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Trains the adaptive duel NPC model on simulated play"};
  std::string out_path, model_path;
  TrainOptions train_opts;
  EvalOptions eval;
  double target = 0.5;
  app.add_option("--out", out_path, "write the trained model here");
  app.add_option("--model", model_path, "evaluate this model file instead of training one");
  app.add_option("--seed", train_opts.seed, "training seed");
  app.add_option("--players", train_opts.players, "simulated players in training")
      ->check(CLI::Range(1, 100000));
  app.add_option("--rounds", train_opts.rounds_per_player, "rounds each training player plays")
      ->check(CLI::Range(2, 1000000));
  app.add_option("--smoothing", train_opts.smoothing, "weight of a round in the hit-rate measure")
      ->check(CLI::Range(0.001, 1.0));
  app.add_option("--eval-players", eval.players_per_skill, "players per skill in the evaluation")
      ->check(CLI::Range(0, 100000));
  app.add_option("--eval-rounds", eval.rounds_per_player, "rounds each evaluated player plays")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--target", target, "target win rate")->check(CLI::Range(0.05, 0.95));
  CLI11_PARSE(app, argc, argv);
  if (out_path.empty() == model_path.empty()) {
    std::fprintf(stderr, "adapt_train: give either --out (train) or --model (evaluate)\n");
    return 2;
  }
  try {
    DuelModel model;
    if (!model_path.empty()) {
      model = loadModel(model_path);
    } else {
      FitReport fit;
      model = train(train_opts, &fit);
      saveModel(out_path, model);
      std::printf("trained on %llu rounds (seed %llu): %d Newton steps, log loss %.4f -> %s\n",
                  (unsigned long long)model.trained_rounds, (unsigned long long)model.seed,
                  fit.iterations, fit.log_loss, out_path.c_str());
    }
    if (eval.players_per_skill > 0) printTable(model, eval, target);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adapt_train: %s\n", e.what());
    return 1;
  }
  return 0;
}
