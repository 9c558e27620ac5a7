#include "gateway/epoch_timeline.h"

#include <algorithm>

namespace zonesim::gateway {

bool EpochTimeline::admit(std::uint32_t epoch) {
  if (epoch < epoch_) {
    ++stale_;
    return false;
  }
  if (epoch > epoch_) {
    epoch_ = epoch;
    ++entered_;
    tick_offset_.reset();
    sim_offset_.reset();
  }
  return true;
}

std::optional<std::uint64_t> EpochTimeline::mapTick(std::uint32_t epoch, std::uint64_t tick) {
  if (!admit(epoch)) return std::nullopt;
  // A gateway started after the restarts (one restarted itself) takes its first epoch as it
  // comes: it has told nobody an older tick.
  if (!tick_offset_) tick_offset_ = mapped_any_ ? std::int64_t(newest_tick_ + 1) - std::int64_t(tick) : 0;
  mapped_any_ = true;
  std::uint64_t mapped = std::uint64_t(std::max<std::int64_t>(0, std::int64_t(tick) + *tick_offset_));
  newest_tick_ = std::max(newest_tick_, mapped);
  return mapped;
}

std::optional<MappedTime> EpochTimeline::map(std::uint32_t epoch, std::uint64_t tick,
                                             double sim_time) {
  std::optional<std::uint64_t> mapped_tick = mapTick(epoch, tick);
  if (!mapped_tick) return std::nullopt;
  if (!sim_offset_) sim_offset_ = mapped_sim_ ? newest_sim_ + dt_ - sim_time : 0.0;
  mapped_sim_ = true;
  MappedTime m{*mapped_tick, sim_time + *sim_offset_};
  newest_sim_ = std::max(newest_sim_, m.sim_time);
  return m;
}

}  // namespace zonesim::gateway
