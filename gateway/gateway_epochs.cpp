// The gateway across cluster restarts: sessions stay open while the zones restart from a
// checkpoint (a new cluster epoch), and what the restored world lacks is sent or asked again.
//  - Each player's first announcement in the new epoch says the last input the restored avatar
//    applied; everything the gateway forwarded after it is resent, in order, in a few bursts a
//    little apart (the first may beat the zone's input reader's discovery; the zone applies
//    each sequence number once, so repeats are free). The zone holds an avatar's gap for that.
//  - kResyncSeconds after entering the epoch, cached entities still of an older one are not
//    in the restored world (created after the checkpoint, or their zone is gone) and are
//    dropped; players whose avatar no zone announced get a new one asked for.
#include "common/log.h"
#include "common/timer.h"
#include "gateway/gateway.h"

namespace zonesim::gateway {

namespace {
constexpr double kResyncSeconds = 5.0;
// The bursts of a resend, after the announcement: discovery of a restarted zone's readers
// takes up to a second or two on a loaded machine.
constexpr std::int64_t kResendGapsNs[] = {0, 250'000'000, 750'000'000, 1'500'000'000};
constexpr int kResendBursts = int(std::size(kResendGapsNs));
}  // namespace

void Gateway::adoptRestoredOwner(Session& s, const zonesim_dds_OwnershipEvent& e,
                                 std::uint64_t tick, bool avatar_changed, bool zone_changed) {
  s.respawning = false;
  // The same avatar restored: it lacks the inputs after the one it says it applied. A new
  // avatar (asked anew) starts from whatever input comes next.
  if (!avatar_changed && s.last_input_seq > e.last_input_seq) {
    s.resend_from = e.last_input_seq + 1;
    if (s.resends_left == 0) resending_.push_back(*sessions_.findByPlayer(s.player_id));
    s.resends_left = kResendBursts;
    s.next_resend_ns = nowNs();
  }
  if (!avatar_changed && !zone_changed) return;
  // The client follows its avatar by id and addresses nothing by zone itself, but is told of
  // both, as of a handoff: numbered and resent until acknowledged.
  s.handoff = PendingHandoff{{e.avatar_id, e.from_zone, e.to_zone, tick, e.last_input_seq}, 0};
  sendHandoff(s, nowNs());
  ++s.traffic.handoffs;
}

void Gateway::resendInputs(std::int64_t now_ns) {
  std::erase_if(resending_, [&](SlotHandle h) {
    Session* s = sessions_.get(h);
    if (s == nullptr || s->resends_left == 0) return true;
    if (now_ns < s->next_resend_ns) return false;
    bool first = s->resends_left == kResendBursts;
    std::uint32_t lacking = s->inputs.since(s->resend_from, [&](const InputRecord& in) {
      if (link_.sendInput({s->player_id, s->avatar_id, s->zone, in.seq, in.move_x, in.move_z}) &&
          first)
        ++counters_.inputs_resent;
    });
    if (first) counters_.inputs_unresendable += lacking;
    --s->resends_left;
    int done = kResendBursts - s->resends_left;
    if (s->resends_left > 0) s->next_resend_ns += kResendGapsNs[done] - kResendGapsNs[done - 1];
    return s->resends_left == 0;
  });
}

void Gateway::followEpochs(std::int64_t now_ns) {
  // The timeline counts; the counters show its figures.
  counters_.epoch_stale = timeline_.stale();
  if (timeline_.epochsEntered() != counters_.epochs_entered) {
    counters_.epochs_entered = timeline_.epochsEntered();
    resync_due_ns_ = now_ns + std::int64_t(kResyncSeconds * 1e9);
    ZS_INFO("zones restarted: cluster epoch %u", unsigned(timeline_.epoch()));
    if (recorder_) recorder_->epoch(timeline_.epoch());
  }
  if (resync_due_ns_ == 0 || now_ns < resync_due_ns_) return;
  resync_due_ns_ = 0;
  std::uint32_t epoch = timeline_.epoch();
  counters_.entities_retired += cache_.retireEpochsBefore(epoch, now_ns);
  double sim_now = clock_.simNow(now_ns);
  sessions_.forEach([&](SlotHandle, Session& s) {
    // Announced in this epoch, or already asked: nothing to do. A pending session's request
    // may have died with the zones: asked again, with its own deadline started anew.
    if (s.owner_epoch >= epoch && s.welcomed) return;
    if (!s.welcomed) s.created_ns = now_ns;
    double x = s.spawn_x, z = s.spawn_z;
    if (s.welcomed) avatarPosition(s, sim_now, x, z);
    s.respawning = s.welcomed;
    link_.requestSpawn(
        {s.player_id, float(x), 0.0f, float(z), std::uint8_t(s.kind), s.resumed, s.session_id});
    ++counters_.avatars_reasked;
  });
}

}  // namespace zonesim::gateway
