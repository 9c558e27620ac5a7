#pragma once
// Physics of a scene (`physics:` and rigid-body `populations:`, docs/scene-format.md): the
// engine's settings, the bodies dropped at random, and the hand-placed bodies, joints, cloths and
// explosions.

#include <string>
#include <utility>
#include <vector>

#include "common/scene_geometry.h"

namespace zonesim {

/// Spheres falling under gravity and bouncing on the ground (the physics issue adds shapes).
struct RigidBodyPopulation {
  enum class Shape { Sphere, Box, Capsule };
  int count = 0;
  Shape shape = Shape::Sphere;
  SceneVec3 size{1, 1, 1};  ///< box: full edge lengths (m)
  double length = 1.0;      ///< capsule: length of the inner segment, along local y (m)
  double friction = 0.5;
  double rolling_resistance = 0;  ///< c_rr: spheres and capsules slow as they roll
  double radius = 0.5;  ///< sphere and capsule radius (m)
  double mass = 1.0;
  double restitution = 0.5;
  double linear_damping = 0;      ///< 1/s: v /= 1 + c dt each substep (physics::BodyDesc)
  double angular_damping = 0;     ///< 1/s: w /= 1 + c dt each substep
  double drop_height = 10.0;      ///< start gap between ground and body (lowest of the range)
  double max_drop_height = 10.0;  ///< start heights are drawn uniformly in [drop_height, this]
  SceneBox region;                ///< where they start on x-z (defaults to the world)
};

/// Radius of the sphere around a body's centre that holds its whole shape.
double boundingRadius(const RigidBodyPopulation& p);

/// A named rigid body placed by hand (physics.bodies), for joints and set pieces.
struct SceneBody {
  enum class Shape { Sphere, Box, Capsule, Compound };
  /// One shape of a compound, placed in the body's frame (position and rotation relative to
  /// the body's); a sphere, box or capsule sized as a body of that shape is.
  struct Part {
    Shape shape = Shape::Sphere;
    SceneVec3 position;
    SceneQuat orientation;
    SceneVec3 size{1, 1, 1};
    double radius = 0.5;
    double length = 1.0;
  };
  /// Dynamic bodies are entities; static and kinematic ones are scene geometry that every zone
  /// places itself (a kinematic body's pose is a closed form of time).
  enum class Motion { Dynamic, Static, Kinematic };
  std::string name;
  Shape shape = Shape::Sphere;
  Motion motion = Motion::Dynamic;
  SceneVec3 position;
  SceneQuat orientation;    ///< at the start
  SceneVec3 size{1, 1, 1};  ///< box: full edge lengths (m)
  double radius = 0.5;      ///< sphere and capsule (m)
  double length = 1.0;      ///< capsule: inner segment along local y (m)
  /// compound: its shapes. A dynamic compound's entity sits at the parts' centre of mass (of
  /// uniform density): position + rotation * centre, and turns about it.
  std::vector<Part> parts;
  SceneVec3 velocity;
  SceneVec3 angular_velocity;
  double mass = 1.0;
  double friction = 0.5;
  double rolling_resistance = 0;  ///< c_rr (as RigidBodyPopulation's)
  double restitution = 0.0;
  double linear_damping = 0;   ///< 1/s, dynamic bodies only (as RigidBodyPopulation's)
  double angular_damping = 0;  ///< 1/s, dynamic bodies only
};

/// A joint between named bodies, or a body and the world (physics.joints; one zone only).
struct SceneJoint {
  enum class Type { Distance, Ball, Hinge };
  Type type = Type::Ball;
  int a = 0;                ///< index into PhysicsSettings::bodies
  int b = -1;               ///< index, or -1: joined to the world
  SceneVec3 anchor;         ///< ball, hinge: the world point joined at the start
  SceneVec3 anchor_a;       ///< distance: world point on a at the start (default: a's centre)
  SceneVec3 anchor_b;       ///< distance: world point on b, or in the world
  SceneVec3 axis{0, 0, 1};  ///< hinge: world axis at the start (normalised)
  double length = 0;        ///< distance: rod length (default: |anchor_b - anchor_a|)
  bool collide = true;      ///< false: the two bodies never touch (they overlap at the joint)
};

/// A mass-spring cloth patch (physics.cloths; one zone only).
struct SceneCloth {
  SceneVec3 origin;                ///< particle (0, 0)
  int columns = 10, rows = 10;     ///< particles along column_axis and row_axis
  double spacing = 0.1;            ///< m between neighbours
  SceneVec3 column_axis{1, 0, 0};  ///< normalised
  SceneVec3 row_axis{0, -1, 0};    ///< normalised, not parallel to column_axis
  double particle_mass = 0.01;
  double stiffness = 200, shear_stiffness = 50, bend_stiffness = 10;  ///< N/m
  double damping = 0.05;                                              ///< N s/m along each spring
  double tear_strain = 0;                 ///< springs past this strain are removed; 0: never
  double thickness = 0.02;                ///< m kept between particles and bodies
  double friction = 0.3;                  ///< against bodies
  /// Semi-implicit Euler needs sub-steps as short as the stiffest spring's period allows;
  /// implicit (backward) Euler is stable at any stiffness and step.
  enum class Integrator { SemiImplicitEuler, ImplicitEuler };
  Integrator integrator = Integrator::SemiImplicitEuler;
  int substeps = 0;                       ///< per tick; 0: chosen (semi-implicit) or 1 (implicit)
  std::vector<std::pair<int, int>> pins;  ///< (column, row) held in place
};

/// An explosion at a time and place (physics.explosions): an instant impulse or a blast.
struct SceneExplosion {
  enum class Falloff { Constant, Linear, Quadratic };
  double time = 0;  ///< s of simulated time; fires at the first tick starting at or after it
  SceneVec3 position;
  double radius = 5;
  double impulse = 0;   ///< N s at the centre (instant); 0 when it is a blast
  double force = 0;     ///< N at the centre (blast); 0 when it is an impulse
  double duration = 0;  ///< s a blast lasts
  Falloff falloff = Falloff::Linear;
};

/// The rigid-body engine's approximations (physics/).
struct PhysicsSettings {
  enum class Integrator {
    ExplicitEuler,
    SemiImplicitEuler,
    PositionVerlet,
    VelocityVerlet,
    Rk2,
    Rk4
  };
  enum class Broadphase { BruteForce, SweepAndPrune, UniformGrid, AabbTree };
  /// Contact response (docs/physics.md compares them); same order as physics::SolverKind.
  enum class Solver {
    SoftStep,
    GaussSeidel,
    Sor,
    Jacobi,
    Penalty,
    Projection,
    ConjugateGradient,
    SoftStepWide
  };
  Integrator integrator = Integrator::SemiImplicitEuler;
  Broadphase broadphase = Broadphase::SweepAndPrune;
  int substeps = 1;
  int velocity_iterations = 10;
  int position_iterations = 2;
  bool sleep = true;  ///< resting islands sleep and cost (almost) nothing
  /// Euler's gyroscopic term (physics::WorldSettings::gyroscopic): off-axis spins precess.
  bool gyroscopic = false;
  /// Scenes that name none get the wide soft step, or the soft step where a body has rolling
  /// resistance, which the wide step does not solve (resolveDefaultSolver).
  Solver solver = Solver::SoftStepWide;
  bool solver_named = false;  ///< the scene file names `solver`: the loader keeps it
  double sor_omega = 1.3;                  ///< over-relaxation factor of the sor solver
  double joint_hertz = 60;                 ///< soft_step: joint spring frequency
  double joint_damping_ratio = 2;          ///< soft_step: joint spring damping ratio
  double linear_drag = 0;     ///< N s/m: F = -k v on every dynamic body (physics::ForceModel)
  double quadratic_drag = 0;  ///< N s^2/m^2: F = -c |v| v on every dynamic body
  /// m; 0: off. Contacts whose bodies moved less than this relative to each other keep their
  /// manifold instead of the narrowphase (physics::WorldSettings::contact_recycle_distance).
  double contact_recycle_distance = 0;
  std::vector<SceneBody> bodies;           ///< named bodies (entities after the populations)
  std::vector<SceneJoint> joints;          ///< between named bodies
  std::vector<SceneCloth> cloths;          ///< zone-local, not sent to clients
  std::vector<SceneExplosion> explosions;  ///< each zone applies them to its own bodies
};

}  // namespace zonesim
