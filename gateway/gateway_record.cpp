// The gateway's part of a recording (--record, gateway/gateway_recorder.h): each player's view
// as the client holds it, why each entity is in it, and the tick's subscribed cells. Only runs
// when recording; the bandwidth attribution is fed from sendTo and sendView.
#include <algorithm>
#include <cmath>

#include "gateway/gateway.h"
#include "recording_generated.h"

namespace zonesim::gateway {

void Gateway::recordView(const Session& s, const ViewPoint& at) {
  using recording::VisibleReason;
  recorded_visible_.clear();
  s.view.forEachKnown([&](std::uint64_t id) {
    const CachedEntity* e = cache_.find(id);
    if (e == nullptr) return;  // a despawn the client has not acknowledged: gone from the world
    const dr::V3 p = predictedPosition(*e, at.sim_now);
    const std::uint8_t kind = e->state.kind;
    const double aura = at.aura[std::min<std::size_t>(kind, at.aura.size() - 1)];
    const double d = std::hypot(p.x - at.x, p.z - at.z);
    // The rule that admits it: the budget's ranking, the nearer of aura and nimbus, or the
    // hysteresis band that keeps what is held until it is clearly out.
    VisibleReason why = VisibleReason::Cell;
    if (config_.budget.enabled())
      why = VisibleReason::Priority;
    else if (d <= std::min(aura, at.nimbus))
      why = aura < at.nimbus ? VisibleReason::Aura : VisibleReason::Nimbus;
    recorded_visible_.push_back({id, float(p.x), float(p.z), kind, std::uint8_t(why)});
  });
  std::sort(recorded_visible_.begin(), recorded_visible_.end(),
            [](const RecordedVisible& a, const RecordedVisible& b) { return a.id < b.id; });
  recorder_->view(s.player_id, s.avatar_id, at.x, at.z, at.nimbus, recorded_visible_,
                  s.traffic.bytes_out);
}

void Gateway::recordTick(double sim_now) {
  interest_.cellsHeld(recorded_cells_);
  recorder_->endTick(clock_.tick(), sim_now, recorded_cells_);
}

}  // namespace zonesim::gateway
