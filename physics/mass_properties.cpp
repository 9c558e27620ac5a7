#include "physics/mass_properties.h"

#include <numbers>
#include <vector>

namespace zonesim::physics {

namespace {

/// A compound's parts summed: masses, the mass-weighted centre, and each part's tensor turned
/// into the body frame (R I R^T) and moved to the common centre (parallel axes:
/// m (|d|^2 E - d d^T) for a part whose centre is d from it).
MassProperties compoundProperties(const std::vector<ShapePart>& parts, double density) {
  MassProperties out;
  std::vector<MassProperties> each;
  each.reserve(parts.size());
  for (const ShapePart& p : parts) {
    each.push_back(computeMassProperties(p.shape, density));
    out.mass += each.back().mass;
    out.centre += each.back().mass * p.position;
  }
  if (out.mass <= 0.0) return out;
  out.centre /= out.mass;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const ShapePart& p = parts[k];
    const MassProperties& m = each[k];
    const Eigen::Matrix3d r = p.orientation.normalized().toRotationMatrix();
    const Vec3 d = p.position - out.centre;
    out.inertia += r * m.inertia * r.transpose() +
                   m.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return out;
}

}  // namespace

MassProperties computeMassProperties(const Shape& shape, double density) {
  constexpr double pi = std::numbers::pi;
  MassProperties out;
  Vec3 diagonal = Vec3::Zero();
  switch (shape.type) {
    case ShapeType::Sphere: {
      const double r = shape.radius;
      out.mass = density * 4.0 / 3.0 * pi * r * r * r;
      diagonal = Vec3::Constant(0.4 * out.mass * r * r);
      break;
    }
    case ShapeType::Box: {
      const Vec3 h = shape.half_extents;
      out.mass = density * 8.0 * h.x() * h.y() * h.z();
      // Full side 2h: m/12 * ((2b)^2 + (2c)^2) = m/3 * (b^2 + c^2).
      diagonal = Vec3(h.y() * h.y() + h.z() * h.z(), h.x() * h.x() + h.z() * h.z(),
                      h.x() * h.x() + h.y() * h.y()) *
                 (out.mass / 3.0);
      break;
    }
    case ShapeType::Capsule: {
      const double r = shape.radius;
      const double h = shape.half_height;
      const double cylinder = density * pi * r * r * 2.0 * h;
      const double spheres = density * 4.0 / 3.0 * pi * r * r * r;
      out.mass = cylinder + spheres;
      const double axial = cylinder * r * r / 2.0 + spheres * 0.4 * r * r;
      // Each hemisphere: 2/5 m r^2 about its base, shifted to the capsule centre through its
      // centroid (3r/8 from the base): 2/5 m r^2 + m (h^2 + 3hr/4) for the pair.
      const double side =
          cylinder * (r * r / 4.0 + h * h / 3.0) + spheres * (0.4 * r * r + h * h + 0.75 * h * r);
      diagonal = Vec3(side, axial, side);
      break;
    }
    case ShapeType::Plane:
      break;
    case ShapeType::Compound:
      return compoundProperties(*shape.parts, density);
  }
  out.inertia = diagonal.asDiagonal();
  return out;
}

}  // namespace zonesim::physics
