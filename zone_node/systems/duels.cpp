#include "zone_node/systems/duels.h"

#include "ai/adapt/model_file.h"

namespace zonesim::zone {

namespace {

// Streams of the duels start here, apart from the entities' (which use their ids).
constexpr std::uint64_t kDuelStreamBase = 0xd0e1'0000'0000ull;

ai::adapt::AdaptMode modeOf(AdaptationSettings::Mode m) {
  switch (m) {
    case AdaptationSettings::Mode::RubberBand:
      return ai::adapt::AdaptMode::RubberBand;
    case AdaptationSettings::Mode::Model:
      return ai::adapt::AdaptMode::Model;
    case AdaptationSettings::Mode::Off:
      break;
  }
  return ai::adapt::AdaptMode::Off;
}

}  // namespace

DuelSystem::DuelSystem(const AdaptationSettings& settings)
    : enabled_(settings.enabled), settings_(settings) {
  adapt_.mode = modeOf(settings.mode);
  adapt_.target_win_rate = settings.target_win_rate;
  adapt_.guard.max_step = settings.max_step;
  adapt_.band_window = settings.band_window;
  adapt_.band_gain = settings.band_gain;
  // Every rank loads it, duels or not, so that a bad file stops the whole cluster alike.
  if (enabled_ && !settings.model.empty())
    model_ = std::make_unique<ai::adapt::DuelModel>(ai::adapt::loadModel(settings.model));
}

DuelSystem::~DuelSystem() = default;

void DuelSystem::add(std::size_t index, std::uint64_t seed) {
  const DuelSpec& spec = settings_.duels[index];
  DuelFigures f;
  f.index = index;
  f.skill = spec.skill;
  duels_.push_back({f,
                    ai::adapt::playerAccuracy(spec.skill),
                    Pcg32(seed, kDuelStreamBase + index),
                    ai::adapt::DuelAdapter(adapt_, model_.get()),
                    {}});
}

void DuelSystem::step(StepContext&) {
  for (Duel& d : duels_) {
    if (!d.round.exchange(d.rng, d.accuracy, d.adapter.params())) continue;
    const ai::adapt::RoundResult& r = d.round.result();
    ++d.figures.rounds;
    d.figures.player_wins += r.player_won ? 1 : 0;
    d.adapter.onRound(r);
    d.round = {};
  }
}

std::vector<DuelFigures> DuelSystem::figures() const {
  std::vector<DuelFigures> out;
  for (const Duel& d : duels_) {
    DuelFigures f = d.figures;
    f.npc = d.adapter.params();
    f.guard = d.adapter.guardStats();
    out.push_back(f);
  }
  return out;
}

}  // namespace zonesim::zone
