#include "clients/remote_view.h"

#include <cmath>

namespace zonesim::clients {

Point3 RemoteView::extrapolate(const Remote& r, std::int64_t now_ns) {
  double dt = double(now_ns - r.received_ns) * 1e-9;
  if (dt < 0) dt = 0;
  const proto::Vec3f &p = r.state.pos(), &v = r.state.vel();
  return {p.x() + v.x() * dt, p.y() + v.y() * dt, p.z() + v.z() * dt};
}

void RemoteView::spawn(const proto::EntityState& s, std::int64_t now_ns) {
  entities_.insert_or_assign(s.id(), Remote{s, now_ns});
}

std::optional<double> RemoteView::update(const proto::EntityState& s, std::int64_t now_ns) {
  auto it = entities_.find(s.id());
  if (it == entities_.end()) return std::nullopt;
  Point3 before = extrapolate(it->second, now_ns);
  it->second = Remote{s, now_ns};
  double dx = before.x - s.pos().x(), dy = before.y - s.pos().y(), dz = before.z - s.pos().z();
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

bool RemoteView::despawn(std::uint64_t id) {
  return entities_.erase(id) > 0;
}

std::optional<Point3> RemoteView::predicted(std::uint64_t id, std::int64_t now_ns) const {
  auto it = entities_.find(id);
  if (it == entities_.end()) return std::nullopt;
  return extrapolate(it->second, now_ns);
}

}  // namespace zonesim::clients
