#pragma once
// Ball-and-socket and hinge joints, solved in the same Gauss-Seidel iterations as contacts and
// distance joints, warm started, with a Baumgarte bias on the drift (as distance joints: the
// errors stay small, and bilateral rows need no split-impulse bookkeeping).
//
// A ball joint keeps two anchor points together: three linear rows along the world axes. A
// hinge adds two angular rows that stop relative rotation about the two directions
// perpendicular to its axis; their error is the small-angle misalignment a_A x a_B.

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "common/math.h"
#include "physics/body_storage.h"
#include "physics/distance_joints.h"
#include "physics/joint_row.h"
#include "physics/soft_joint_anchor.h"
#include "physics/softness.h"

namespace zonesim::physics {

/// A ball-and-socket joint: anchors in each body's frame (a world point when b is kNoBody).
struct BallJoint {
  BodyIndex a = 0;
  BodyIndex b = kNoBody;
  Vec3 local_a = Vec3::Zero();
  Vec3 local_b = Vec3::Zero();
};

/// A hinge: a ball joint plus an axis, given in each body's frame (world axis when b is
/// kNoBody), that the two bodies keep aligned; rotation about it is free.
struct HingeJoint {
  BodyIndex a = 0;
  BodyIndex b = kNoBody;
  Vec3 local_a = Vec3::Zero();
  Vec3 local_b = Vec3::Zero();
  Vec3 axis_a = Vec3::UnitZ();
  Vec3 axis_b = Vec3::UnitZ();
};

/// The ball and hinge joints of a world with their per-step rows.
class RigidJoints {
 public:
  /// Adds a ball joint and returns its index among the ball joints.
  std::uint32_t addBall(const BallJoint& joint);
  /// Adds a hinge and returns its index among the hinges.
  std::uint32_t addHinge(const HingeJoint& joint);
  /// Values a joint carries from one step to the next: its rows' impulses (3 for a ball, 5
  /// for a hinge; the rest 0) and the soft step's point and angular impulses.
  static constexpr std::size_t kWarmValues = 11;
  /// The warm start of ball i (hinge: i = balls + hinge index).
  std::array<double, kWarmValues> warmState(std::size_t i) const;
  /// Sets it, as warmState() gave it in another world holding the same joint.
  void setWarmState(std::size_t i, const std::array<double, kWarmValues>& values);
  /// Number of ball joints (the hinges come after them).
  std::size_t ballCount() const { return balls_.size(); }
  /// True when there is no joint (the world skips the calls).
  bool empty() const { return balls_.empty() && hinges_.empty(); }
  /// Bodies held by a joint get a 1 in touched (sized to the body count).
  void markBodies(std::span<std::uint8_t> touched) const;
  /// Calls f(a, b) for every joint's bodies (b may be kNoBody).
  template <typename F>
  void forEachPair(F f) const {
    for (const BallJoint& j : balls_) f(j.a, j.b);
    for (const HingeJoint& j : hinges_) f(j.a, j.b);
  }
  /// Builds the rows at the current positions; beta is the Baumgarte fraction per step.
  void prepare(const BodyStorage& bodies, double dt, double beta);
  /// Applies last step's impulses.
  void warmStart(BodyStorage& bodies);
  /// One Gauss-Seidel pass over every row.
  void iterate(BodyStorage& bodies);
  /// Soft step, at each sub-step: fixes every joint's anchors, axes and effective masses at
  /// the bodies' motion so far (dp, dtheta) and applies the last sub-step's impulses.
  void prepareSoft(BodyStorage& bodies, std::span<const Vec3> dp, std::span<const Vec3> dtheta);
  /// Soft step: one pass over every joint, biased by the joint spring `soft`, or a relax pass
  /// without bias.
  void iterateSoft(BodyStorage& bodies, const Softness& soft, bool use_bias);

 private:
  // One bilateral row with the bodies it joins and its impulse (kept for the warm start).
  struct Row : JointRow {
    BodyIndex a, b;  // b may be kNoBody.
    double impulse;
  };
  struct Anchor {
    BodyIndex a, b;
    Vec3 local_a, local_b;
  };
  /// Where joint i's rows start, and how many it has.
  std::pair<std::size_t, std::size_t> rowsOf(std::size_t i) const;
  void addPointRows(const BodyStorage& bodies, const Anchor& anchor, double rate,
                    std::size_t& next);
  void addAngularRow(const BodyStorage& bodies, BodyIndex a, BodyIndex b, const Vec3& u,
                     double error, double rate, std::size_t& next);

  std::vector<BallJoint> balls_;
  std::vector<HingeJoint> hinges_;
  std::vector<Row> rows_;
  std::vector<double> stored_;  // Row impulses of the last step, in row order.
  // A joint as the soft step's sub-step sees it (balls then hinges), with its impulses of the
  // last sub-step: the point impulse on B and the hinge's angular impulse on B (world axes),
  // each the reverse on A. Bodies do not move within a sub-step's passes, so the geometry is
  // found once per sub-step.
  struct SoftJoint {
    SoftAnchor a, b;
    Eigen::Matrix3d point_mass;  // inverse of the anchors' inverse mass matrix
    Vec3 axis[2];                // hinge: directions that must not turn (unused for a ball)
    double axis_error[2], axis_mass[2];
    Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
  };
  void freeze(SoftJoint& joint, const BodyStorage& bodies, std::span<const Vec3> dp,
              std::span<const Vec3> dtheta, BodyIndex a, BodyIndex b, const Vec3& local_a,
              const Vec3& local_b) const;
  std::vector<SoftJoint> soft_;
};

}  // namespace zonesim::physics
