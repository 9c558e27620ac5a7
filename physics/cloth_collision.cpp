#include "physics/cloth_collision.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/world.h"

namespace zonesim::physics {

namespace {

double boxDistance(const Vec3& half, const Vec3& local, Vec3& local_normal) {
  const Vec3 q = local.cwiseAbs() - half;
  if (q.maxCoeff() > 0.0) {  // Outside: to the closest point of the box.
    const Vec3 out = local - local.cwiseMax(-half).cwiseMin(half);
    const double d = out.norm();
    local_normal = out / d;
    return d;
  }
  int axis = 0;  // Inside: out through the nearest face.
  q.maxCoeff(&axis);
  local_normal = Vec3::Zero();
  local_normal[axis] = local[axis] < 0.0 ? -1.0 : 1.0;
  return q[axis];
}

double boundOf(const Shape& s) {
  switch (s.type) {
    case ShapeType::Sphere:
      return s.radius;
    case ShapeType::Box:
      return s.half_extents.norm();
    case ShapeType::Capsule:
      return s.radius + s.half_height;
    case ShapeType::Plane:
      break;
    case ShapeType::Compound: {
      double bound = 0.0;
      for (const ShapePart& p : *s.parts)
        bound = std::max(bound, p.position.norm() + boundOf(p.shape));
      return bound;
    }
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

double signedDistance(const Shape& shape, const Vec3& position, const Quat& orientation,
                      const Vec3& p, Vec3& normal) {
  switch (shape.type) {
    case ShapeType::Sphere:
    case ShapeType::Capsule: {
      Vec3 centre = position;
      if (shape.type == ShapeType::Capsule) {
        const Vec3 axis = orientation * Vec3::UnitY();
        const double t = std::clamp(axis.dot(p - position), -shape.half_height, shape.half_height);
        centre = position + t * axis;
      }
      const Vec3 d = p - centre;
      const double r = d.norm();
      // At the centre any direction is as good; up keeps the choice deterministic.
      normal = r > 0.0 ? Vec3(d / r) : Vec3::UnitY();
      return r - shape.radius;
    }
    case ShapeType::Box: {
      Vec3 local_normal;
      const double d =
          boxDistance(shape.half_extents, orientation.conjugate() * (p - position), local_normal);
      normal = orientation * local_normal;
      return d;
    }
    case ShapeType::Plane:
      normal = orientation * Vec3::UnitY();
      return normal.dot(p - position);
    case ShapeType::Compound: {
      // The nearest part: exact outside every part, a bound inside where parts overlap.
      double nearest = std::numeric_limits<double>::infinity();
      for (const ShapePart& part : *shape.parts) {
        Vec3 n;
        const double d = signedDistance(part.shape, position + orientation * part.position,
                                        orientation * part.orientation, p, n);
        if (d < nearest) nearest = d, normal = n;
      }
      return nearest;
    }
  }
  normal = Vec3::UnitY();
  return std::numeric_limits<double>::infinity();
}

void ClothColliders::gather(const BodyStorage& bodies) {
  colliders_.clear();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    colliders_.push_back(Collider{static_cast<BodyIndex>(i), bodies.shape[i], bodies.position[i],
                                  bodies.linear_velocity[i], bodies.angular_velocity[i],
                                  bodies.orientation[i], boundOf(bodies.shape[i]),
                                  bodies.type[i] == BodyType::Dynamic});
  }
  impulse_.assign(colliders_.size(), Vec3::Zero());
  angular_impulse_.assign(colliders_.size(), Vec3::Zero());
  contacts_ = 0;
}

void ClothColliders::resolve(std::vector<Vec3>& x, std::vector<Vec3>& v,
                             const std::vector<double>& inv_mass, double thickness,
                             double friction) {
  for (std::size_t k = 0; k < colliders_.size(); ++k) {
    const Collider& c = colliders_[k];
    const double reach = c.bound + thickness;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (inv_mass[i] == 0.0) continue;  // Pins hold whatever touches them.
      if (c.shape.type != ShapeType::Plane && (x[i] - c.position).squaredNorm() > reach * reach)
        continue;
      Vec3 n;
      const double d = signedDistance(c.shape, c.position, c.orientation, x[i], n);
      if (d >= thickness) continue;
      ++contacts_;
      x[i] += (thickness - d) * n;
      const Vec3 arm = x[i] - c.position;
      const Vec3 surface_v = c.linear_velocity + c.angular_velocity.cross(arm);
      const Vec3 rel = v[i] - surface_v;
      const double vn = rel.dot(n);
      if (vn >= 0.0) continue;  // Already leaving: the position fix is enough.
      const Vec3 vt = rel - vn * n;
      const double slide = vt.norm();
      // Coulomb: friction removes at most mu times the normal change from the sliding speed.
      const double keep = slide > 0.0 ? std::max(0.0, 1.0 - friction * (-vn) / slide) : 0.0;
      const Vec3 dv = -vn * n - (1.0 - keep) * vt;
      v[i] += dv;
      if (!c.dynamic) continue;
      const Vec3 j = -dv / inv_mass[i];  // What the particle gave the body.
      impulse_[k] += j;
      angular_impulse_[k] += arm.cross(j);
    }
  }
}

void ClothColliders::applyReactions(World& world, double wake_speed) {
  BodyStorage& b = world.bodies();
  for (std::size_t k = 0; k < colliders_.size(); ++k) {
    if (!colliders_[k].dynamic) continue;
    const BodyIndex i = colliders_[k].body;
    const Vec3 dv = b.inv_mass[i] * impulse_[k];
    const Vec3 dw = b.inv_inertia_world[i] * angular_impulse_[k];
    if (world.asleep(i)) {
      if (dv.norm() < wake_speed && dw.norm() < wake_speed) continue;
      world.wake(i);
    }
    b.linear_velocity[i] += dv;
    b.angular_velocity[i] += dw;
  }
  std::fill(impulse_.begin(), impulse_.end(), Vec3::Zero());
  std::fill(angular_impulse_.begin(), angular_impulse_.end(), Vec3::Zero());
}

}  // namespace zonesim::physics
