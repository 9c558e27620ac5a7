#pragma once
// The joint scenes the stability tests and the joint benchmark share, built as their sources
// build them (one builder, so "the ball and chain" means the same bodies everywhere), with
// what a run of them is judged by: the widest gap between any joint's two anchors, the energy
// (a solver that blows up gains it), and the fastest body.

#include <functional>
#include <vector>

#include "common/math.h"
#include "physics/world.h"

namespace zonesim::physics {

/// A world of jointed bodies and the anchors of its point joints.
class JointScene {
 public:
  explicit JointScene(const WorldSettings& settings) : world_(settings) {}
  World& world() { return world_; }
  const World& world() const { return world_; }
  /// Widest gap (m) between the two anchors of any joint.
  double worstGap() const;
  /// Kinetic plus gravitational energy (J) of the movable bodies.
  double energy() const;
  /// Fastest body speed (m/s).
  double fastestSpeed() const;

 protected:
  /// Adds a ball joint and remembers its anchors (local_b is a world point when b is kNoBody).
  void addBall(BodyIndex a, BodyIndex b, const Vec3& local_a, const Vec3& local_b);
  /// Adds a hinge about world z through the world point `at`, and keeps the two bodies from
  /// touching (neighbouring links overlap at their hinge); a is kNoBody for a fixed pivot.
  void addHingeZ(BodyIndex a, BodyIndex b, const Vec3& at);

 private:
  struct Anchors {
    BodyIndex a, b;
    Vec3 local_a, local_b;
  };
  World world_;
  std::vector<Anchors> anchors_;
};

/// Solver2D's ball and chain in 3D: 30 capsule links (radius 0.125 m, 1 m between their hinge
/// points, density 20) hinged end to end about z from a fixed pivot, and a ball of radius
/// 4 m hinged to the last link, dense enough to weigh 170 links. It starts horizontal, falls
/// and swings.
class BallAndChain : public JointScene {
 public:
  explicit BallAndChain(const WorldSettings& settings);
};

/// Box2D's joint grid in 3D: n x n spheres (radius 0.4 m, 1 m apart) in the x-y plane, each
/// joined to its left and upper neighbours by ball joints at the midpoints; the 7 middle
/// spheres of the top row are fixed. It falls from flat and hangs from them.
class JointGrid : public JointScene {
 public:
  JointGrid(const WorldSettings& settings, int n);
};

/// What a run of a joint scene showed, sampled every few steps.
struct JointRunRecord {
  double worst_gap = 0.0;          ///< m, the widest joint gap seen
  double final_gap = 0.0;          ///< m, after the last step
  double worst_speed = 0.0;        ///< m/s, the fastest body seen
  double worst_energy_gain = 0.0;  ///< J, the most the energy rose above its start
  bool finite = true;              ///< no body went non-finite
  double seconds_per_step = 0.0;   ///< wall time
};

/// Steps the scene `steps` times at 1/60 s, sampling every `every` steps (and after the last);
/// `progress`, when set, hears each sample's step.
JointRunRecord runJointScene(JointScene& scene, int steps, int every,
                             const std::function<void(int, const JointRunRecord&)>& progress = {});

}  // namespace zonesim::physics
