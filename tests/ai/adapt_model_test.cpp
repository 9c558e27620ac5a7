// The model file round-trips and names the line of any problem; training on a small
// fixed-seed run brings players of every skill to the target win rate.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "ai/adapt/evaluate.h"
#include "ai/adapt/learner.h"
#include "ai/adapt/model_file.h"
#include "ai/parse_error.h"

namespace zonesim::ai::adapt {
namespace {

TEST(AdaptModelFile, WriteThenReadIsEqual) {
  TrainOptions o;
  o.players = 8;
  o.rounds_per_player = 50;
  const DuelModel model = train(o);
  std::stringstream text;
  writeModel(text, model);
  const DuelModel back = readModel(text, "mem");
  for (std::size_t i = 0; i < kBasisSize; ++i) EXPECT_EQ(back.weights[i], model.weights[i]) << i;
  EXPECT_EQ(back.trained_rounds, model.trained_rounds);
  EXPECT_EQ(back.seed, model.seed);
  EXPECT_EQ(back.smoothing, model.smoothing);
}

// The error names the file, the line and what is wrong.
void expectError(const std::string& text, int line, const std::string& what) {
  std::istringstream in(text);
  try {
    readModel(in, "m.txt");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find("m.txt:" + std::to_string(line) + ": " + what),
              std::string::npos)
        << e.what();
  }
}

TEST(AdaptModelFile, MalformedFilesNameTheLine) {
  const std::string w = "weights 0 0 0 0 0 0 0 0 0 0\n";
  const std::string head = "zonesim-adapt-model 1\nbasis cubic-hd\n";
  expectError("", 0, "empty model file");
  expectError("# only a comment\nbasis cubic-hd\n", 2, "expected the version line");
  expectError("zonesim-adapt-model 2\n", 1, "model version 2 is not supported");
  expectError(head + "weights 0 0 0\n", 3, "weights: expected 10 numbers, got 3");
  expectError(head + "weights 0 0 nan 0 0 0 0 0 0 0\n", 3, "weights: value 3 'nan'");
  expectError(head + "weights 0 0 inf 0 0 0 0 0 0 0\n", 3, "weights: value 3 'inf'");
  expectError(head + "weights 0 0 1e999 0 0 0 0 0 0 0\n", 3, "weights: value 3 '1e999'");
  expectError(head + w + "smoothing 0\n", 4, "smoothing: '0' is not a number in (0, 1]");
  expectError(head + w + "smoothing 0.1\nseed -4\n", 5, "seed: '-4'");
  expectError(head + w + "smoothing 0.1\nlearning_rate 3\n", 5, "unknown key 'learning_rate'");
  expectError(head + w + w, 4, "weights: given twice");
  expectError("zonesim-adapt-model 1\nbasis quintic\n", 2, "basis: 'quintic' is unknown");
  expectError(head + "smoothing 0.1\n", 3, "weights: missing");
}

// The inversion agrees with the model: at the difficulty it returns, the prediction is the
// target, or the target lies beyond [0, 1] on that side.
TEST(AdaptModel, DifficultyForInvertsWinProbability) {
  TrainOptions o;
  o.players = 16;
  o.rounds_per_player = 200;
  const DuelModel model = train(o);
  for (double h : {0.15, 0.3, 0.5, 0.7, 0.85})
    for (double target : {0.3, 0.5, 0.7}) {
      const double d = model.difficultyFor(h, target);
      ASSERT_TRUE(d >= 0 && d <= 1) << h;
      if (d == 0)
        EXPECT_LE(model.winProbability(h, 0), target);
      else if (d == 1)
        EXPECT_GE(model.winProbability(h, 1), target);
      else
        EXPECT_NEAR(model.winProbability(h, d), target, 1e-4) << "h " << h;
    }
}

TEST(AdaptModelFile, MissingFileIsNamed) {
  EXPECT_THROW(loadModel("/nonexistent/model.txt"), ParseError);
}

// A small fixed-seed training run, then fresh players of three skills: with the model every
// skill wins within 5 points of 50 %; without adaptation the weak and the strong do not.
TEST(AdaptTraining, SmallRunConvergesToTheBand) {
  TrainOptions o;
  o.players = 32;
  o.rounds_per_player = 300;
  FitReport fit;
  const DuelModel model = train(o, &fit);
  EXPECT_LT(fit.iterations, o.newton_iterations);  // Newton converged before its cap
  EvalOptions e;
  e.players_per_skill = 10;
  e.rounds_per_player = 200;
  const std::vector<double> skills{0.1, 0.5, 0.9};
  AdaptSettings s;
  s.mode = AdaptMode::Model;
  for (const SkillOutcome& out : evaluate(skills, s, &model, e)) {
    EXPECT_EQ(out.rounds, 2000u);
    EXPECT_NEAR(out.winRate(), 0.5, 0.05) << "skill " << out.skill << ": " << out.player_wins;
    EXPECT_EQ(out.fallbacks, 0u);
  }
  s.mode = AdaptMode::Off;
  const std::vector<SkillOutcome> off = evaluate(skills, s, &model, e);
  EXPECT_LT(off.front().winRate(), 0.4);
  EXPECT_GT(off.back().winRate(), 0.6);
}

}  // namespace
}  // namespace zonesim::ai::adapt
