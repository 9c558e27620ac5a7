#include "clients/remote_view.h"

#include <algorithm>

namespace zonesim::clients {

namespace {
Point3 point(const dr::V3& v) {
  return {v.x, v.y, v.z};
}
}  // namespace

dr::V3 RemoteView::model(const dr::WireEntity& e, double now) const {
  double dt = std::max(0.0, (now - double(e.tick)) * r_.sim_dt);
  return dr::predictPosition(e.state, e.model.order, dt);
}

dr::V3 RemoteView::modelVelocity(const dr::WireEntity& e, double now) const {
  double dt = std::max(0.0, (now - double(e.tick)) * r_.sim_dt);
  return dr::predictVelocity(e.state, e.model.order, dt);
}

dr::V3 RemoteView::shownPosition(const Remote& r, double now) const {
  dr::V3 target = model(r.latest, now);
  double since = (now - r.blend_start) * r_.sim_dt;
  if (!r.blending || since >= r_.blend_s || since < 0) return target;
  // Projective velocity blending: project from where the entity was shown with a velocity
  // blended from the old towards the new one, then blend that projection into the new model.
  double lambda = since / r_.blend_s;
  dr::V3 v1 = r.latest.state.vel;
  dr::V3 vb{r.from_vel.x + (v1.x - r.from_vel.x) * lambda,
            r.from_vel.y + (v1.y - r.from_vel.y) * lambda,
            r.from_vel.z + (v1.z - r.from_vel.z) * lambda};
  dr::V3 a = r.latest.model.order == dr::Order::Second ? r.latest.state.acc : dr::V3{};
  double h = 0.5 * since * since;
  dr::V3 projected{r.from_pos.x + vb.x * since + a.x * h, r.from_pos.y + vb.y * since + a.y * h,
                   r.from_pos.z + vb.z * since + a.z * h};
  return {projected.x + (target.x - projected.x) * lambda,
          projected.y + (target.y - projected.y) * lambda,
          projected.z + (target.z - projected.z) * lambda};
}

void RemoteView::spawn(const dr::WireEntity& e, double /*now*/) {
  entities_.insert_or_assign(e.id, Remote{e, {}, {}, 0, false});
}

std::optional<double> RemoteView::update(const dr::WireEntity& e, double now) {
  auto it = entities_.find(e.id);
  if (it == entities_.end()) return std::nullopt;
  Remote& r = it->second;
  // A resent or reordered older state must not replace a newer one, and a repeat of the held
  // sample (resent because its ack was late) is no news: no correction, no new blend.
  if (e.tick <= r.latest.tick) return std::nullopt;
  dr::V3 before = shownPosition(r, now);
  dr::V3 before_vel = modelVelocity(r.latest, now);
  r.latest = e;
  if (r_.blend) {
    r.from_pos = before;
    r.from_vel = before_vel;
    r.blend_start = now;
    r.blending = true;
  }
  return dr::distance(before, model(e, now));
}

bool RemoteView::despawn(std::uint64_t id) {
  return entities_.erase(id) > 0;
}

std::optional<Point3> RemoteView::shown(std::uint64_t id, double now) const {
  auto it = entities_.find(id);
  if (it == entities_.end()) return std::nullopt;
  return point(shownPosition(it->second, now));
}

std::optional<Point3> RemoteView::predicted(std::uint64_t id, double now) const {
  auto it = entities_.find(id);
  if (it == entities_.end()) return std::nullopt;
  return point(model(it->second.latest, now));
}

const dr::WireEntity* RemoteView::find(std::uint64_t id) const {
  auto it = entities_.find(id);
  return it == entities_.end() ? nullptr : &it->second.latest;
}

}  // namespace zonesim::clients
