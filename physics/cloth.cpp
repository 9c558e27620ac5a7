#include "physics/cloth.h"

#include <algorithm>
#include <numeric>

#include "physics/cloth_collision.h"

namespace zonesim::physics {

Cloth::Cloth(const ClothDesc& desc) : desc_(desc) {
  const int n = desc.columns * desc.rows;
  x_.resize(n);
  v_.assign(n, Vec3::Zero());
  f_.assign(n, Vec3::Zero());
  inv_mass_.assign(n, 1.0 / desc.particle_mass);
  for (int r = 0; r < desc.rows; ++r) {
    for (int c = 0; c < desc.columns; ++c) {
      x_[index(c, r)] = desc.origin + desc.spacing * (c * desc.column_axis + r * desc.row_axis);
    }
  }
  for (int r = 0; r < desc.rows; ++r) {
    for (int c = 0; c < desc.columns; ++c) {
      addSpring(c, r, c + 1, r, desc.stiffness, SpringKind::Structural);
      addSpring(c, r, c, r + 1, desc.stiffness, SpringKind::Structural);
      addSpring(c, r, c + 1, r + 1, desc.shear_stiffness, SpringKind::Shear);
      addSpring(c + 1, r, c, r + 1, desc.shear_stiffness, SpringKind::Shear);
      addSpring(c, r, c + 2, r, desc.bend_stiffness, SpringKind::Bend);
      addSpring(c, r, c, r + 2, desc.bend_stiffness, SpringKind::Bend);
    }
  }
}

void Cloth::addSpring(int c0, int r0, int c1, int r1, double stiffness, SpringKind kind) {
  if (stiffness <= 0.0 || c1 >= desc_.columns || r1 >= desc_.rows || c0 >= desc_.columns) return;
  const std::uint32_t a = index(c0, r0), b = index(c1, r1);
  springs_.push_back(ClothSpring{a, b, (x_[b] - x_[a]).norm(), stiffness, kind});
}

void Cloth::accumulateForces() {
  for (std::size_t i = 0; i < x_.size(); ++i) {
    f_[i] = inv_mass_[i] > 0.0 ? Vec3(desc_.gravity / inv_mass_[i]) : Vec3::Zero();
  }
  for (const ClothSpring& s : springs_) {
    const Vec3 d = x_[s.b] - x_[s.a];
    const double length = d.norm();
    if (length == 0.0) continue;  // No direction: no force rather than a NaN.
    const Vec3 dir = d / length;
    const double magnitude =
        s.stiffness * (length - s.rest) + desc_.spring_damping * dir.dot(v_[s.b] - v_[s.a]);
    f_[s.a] += magnitude * dir;
    f_[s.b] -= magnitude * dir;
  }
}

void Cloth::step(double dt, int substeps, ClothColliders* colliders) {
  const int n = std::max(1, substeps);
  const double h = dt / n;
  for (int k = 0; k < n; ++k) {
    if (desc_.integrator == ClothIntegrator::ImplicitEuler) {
      stepImplicit(h);
    } else {
      stepSemiImplicit(h);
    }
    if (colliders) colliders->resolve(x_, v_, inv_mass_, desc_.thickness, desc_.friction);
    if (desc_.tear_strain > 0.0) tear();
  }
}

void Cloth::stepSemiImplicit(double h) {
  accumulateForces();
  for (std::size_t i = 0; i < x_.size(); ++i) {
    if (inv_mass_[i] == 0.0) continue;
    v_[i] += h * inv_mass_[i] * f_[i];
    x_[i] += h * v_[i];
  }
}

void Cloth::tear() {
  const double limit = 1.0 + desc_.tear_strain;
  const std::size_t before = springs_.size();
  std::erase_if(springs_,
                [&](const ClothSpring& s) { return (x_[s.b] - x_[s.a]).norm() > limit * s.rest; });
  torn_ += before - springs_.size();
}

int Cloth::pieceCount() const {
  std::vector<std::uint32_t> parent(x_.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const ClothSpring& s : springs_) parent[find(s.a)] = find(s.b);
  int pieces = 0;
  for (std::uint32_t i = 0; i < parent.size(); ++i) pieces += find(i) == i;
  return pieces;
}

Vec3 Cloth::pinForce() const {
  Vec3 total = Vec3::Zero();
  for (const ClothSpring& s : springs_) {
    const Vec3 d = x_[s.b] - x_[s.a];
    const double length = d.norm();
    if (length == 0.0) continue;
    const Vec3 f = s.stiffness * (length - s.rest) * d / length;  // On a, towards b.
    if (inv_mass_[s.a] == 0.0) total += f;
    if (inv_mass_[s.b] == 0.0) total -= f;
  }
  return total;
}

Vec3 Cloth::momentum() const {
  Vec3 p = Vec3::Zero();
  for (std::size_t i = 0; i < x_.size(); ++i) {
    if (inv_mass_[i] > 0.0) p += v_[i] / inv_mass_[i];
  }
  return p;
}

double Cloth::kineticEnergy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < x_.size(); ++i) {
    if (inv_mass_[i] > 0.0) e += 0.5 * v_[i].squaredNorm() / inv_mass_[i];
  }
  return e;
}

}  // namespace zonesim::physics
