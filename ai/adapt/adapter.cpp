#include "ai/adapt/adapter.h"

#include <stdexcept>

namespace zonesim::ai::adapt {

DuelAdapter::DuelAdapter(const AdaptSettings& settings, const DuelModel* model)
    : settings_(settings),
      model_(model),
      // The model reads the measure it was trained on; without one any smoothing will do.
      features_(model ? model->smoothing : 0.05),
      band_(settings.band_window, settings.band_gain),
      guard_(settings.guard),
      params_(settings.guard.defaults) {
  if (settings.mode == AdaptMode::Model && !model)
    throw std::invalid_argument("adaptation mode 'model' needs a model");
}

void DuelAdapter::onRound(const RoundResult& r) {
  features_.observe(r);
  band_.record(r.player_won);
  double d = kDefaultDifficulty;
  switch (settings_.mode) {
    case AdaptMode::Off:
      return;  // the NPC stays as the game made it
    case AdaptMode::RubberBand:
      d = band_.difficulty();
      break;
    case AdaptMode::Model:
      // Before a round is measured the model has nothing to read: hold the defaults.
      if (features_.rounds() > 0)
        d = model_->difficultyFor(features_.hitRate(), settings_.target_win_rate);
      break;
  }
  propose(paramsForDifficulty(d, settings_.guard.ranges));
}

}  // namespace zonesim::ai::adapt
