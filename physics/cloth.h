#pragma once
// A cloth patch as a mass-spring mesh: particles on a grid joined by structural (neighbours),
// shear (diagonals) and bend (two apart) springs, integrated in sub-steps by semi-implicit
// Euler or by implicit (backward) Euler (cloth_implicit.cpp), with pinned particles and
// tearing: a spring stretched past its strain limit is removed, and the mesh may split into
// pieces (counted by union-find).

#include <cstdint>
#include <vector>

#include "common/math.h"

namespace zonesim::physics {

/// How a cloth's sub-step advances the springs.
enum class ClothIntegrator : std::uint8_t {
  /// v += h f(x, v) / m, then x += h v: cheap, stable only while h omega < 2 for the stiffest
  /// mode (a particle on springs of total stiffness k: k < 4 m / h^2).
  SemiImplicitEuler,
  /// Backward Euler on the springs (Baraff and Witkin): the velocity change solves
  /// (M + h D + h^2 K) dv = h (f + h df/dx v) by conjugate gradients. Stable at any stiffness
  /// and step; it damps high frequencies, so a stiff cloth looks heavier, not jittery.
  ImplicitEuler,
};

/// Which springs a cloth grid gets, and their constants.
struct ClothDesc {
  int columns = 10;                      ///< Particles along the patch's width (x).
  int rows = 10;                         ///< Particles along its height (down from the origin).
  double spacing = 0.1;                  ///< m between grid neighbours.
  Vec3 origin = Vec3::Zero();            ///< Particle (0, 0).
  Vec3 column_axis = Vec3::UnitX();      ///< Unit direction from column c to c + 1.
  Vec3 row_axis = -Vec3::UnitY();        ///< Unit direction from row r to r + 1.
  double particle_mass = 0.01;           ///< kg.
  double stiffness = 200.0;              ///< N/m of structural springs.
  double shear_stiffness = 50.0;         ///< N/m of diagonal springs (0: none).
  double bend_stiffness = 10.0;          ///< N/m of two-apart springs (0: none).
  double spring_damping = 0.05;          ///< N s/m along each spring.
  double tear_strain = 0.0;              ///< Remove a spring beyond (length/rest - 1); 0: never.
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);  ///< m/s^2.
  double thickness = 0.02;               ///< m kept between particles and colliding bodies.
  double friction = 0.3;                 ///< Coulomb coefficient against bodies.
  ClothIntegrator integrator = ClothIntegrator::SemiImplicitEuler;
  /// Implicit Euler: conjugate gradients stop at this residual relative to the right-hand side.
  double implicit_tolerance = 1e-10;
  /// Implicit Euler: and after at most this many iterations.
  int implicit_max_iterations = 500;
};

class ClothColliders;

/// Spring families.
enum class SpringKind : std::uint8_t { Structural, Shear, Bend };

/// One spring between particles a and b.
struct ClothSpring {
  std::uint32_t a = 0, b = 0;
  double rest = 0.0;
  double stiffness = 0.0;
  SpringKind kind = SpringKind::Structural;
};

/// A mass-spring cloth patch.
class Cloth {
 public:
  /// Builds the grid at rest (every spring at its rest length).
  explicit Cloth(const ClothDesc& desc);

  /// Index of the particle at (column, row).
  std::uint32_t index(int column, int row) const {
    return static_cast<std::uint32_t>(row * desc_.columns + column);
  }
  /// Fixes a particle in place (infinite mass); it can still be moved by setting its position.
  void pin(std::uint32_t i) { inv_mass_[i] = 0.0; }
  /// Advances by dt in `substeps` sub-steps of the desc's integrator, then tears
  /// over-stretched springs (checked after every sub-step). With colliders, every sub-step ends
  /// by pushing the particles out of the bodies (cloth_collision.h).
  void step(double dt, int substeps, ClothColliders* colliders = nullptr);
  /// The description it was built from.
  const ClothDesc& desc() const { return desc_; }
  /// Total momentum of the free particles (kg m/s).
  Vec3 momentum() const;

  /// Particle positions.
  std::vector<Vec3>& positions() { return x_; }
  /// Particle positions.
  const std::vector<Vec3>& positions() const { return x_; }
  /// Particle velocities.
  std::vector<Vec3>& velocities() { return v_; }
  /// Particle velocities.
  const std::vector<Vec3>& velocities() const { return v_; }
  /// The springs still in the mesh.
  const std::vector<ClothSpring>& springs() const { return springs_; }
  /// Springs removed by tearing so far.
  std::size_t tornCount() const { return torn_; }
  /// Number of connected pieces (particles joined by any remaining spring).
  int pieceCount() const;
  /// Total force the springs exert on the pinned particles (the reaction the pins hold).
  Vec3 pinForce() const;
  /// Kinetic energy of the free particles (J).
  double kineticEnergy() const;
  /// Implicit Euler: conjugate-gradient iterations of the last sub-step, and the residual it
  /// reached relative to the right-hand side.
  int implicitIterations() const { return cg_iterations_; }
  double implicitResidual() const { return cg_residual_; }

 private:
  void addSpring(int c0, int r0, int c1, int r1, double stiffness, SpringKind kind);
  void accumulateForces();
  void stepSemiImplicit(double h);
  /// cloth_implicit.cpp: one backward Euler sub-step of the springs and gravity.
  void stepImplicit(double h);
  /// (M + h D + h^2 K) p for the spring blocks of the current sub-step, pinned rows zero.
  void applySystem(const std::vector<Vec3>& p, std::vector<Vec3>& out) const;
  void tear();

  ClothDesc desc_;
  std::vector<Vec3> x_, v_, f_;
  std::vector<double> inv_mass_;
  std::vector<ClothSpring> springs_;
  std::size_t torn_ = 0;
  // Implicit Euler: h D + h^2 K of each spring (3x3, symmetric), the system's diagonal, and the
  // conjugate-gradient vectors; kept to avoid allocating each sub-step.
  std::vector<Eigen::Matrix3d> blocks_;
  std::vector<Vec3> diagonal_, dv_, r_, z_, p_, q_;
  int cg_iterations_ = 0;
  double cg_residual_ = 0.0;
};

}  // namespace zonesim::physics
