#pragma once
// Distance joints: keep two anchor points (or an anchor and a fixed world point) at a set
// distance. Solved in the same Gauss-Seidel iterations as the contacts, with warm starting.
// Position drift is corrected by a Baumgarte bias: a joint's error stays tiny, so the energy
// the bias injects is negligible, and a bilateral row needs no split-impulse bookkeeping.

#include <cstdint>
#include <span>
#include <vector>

#include "common/math.h"
#include "physics/body_storage.h"
#include "physics/joint_row.h"
#include "physics/soft_joint_anchor.h"
#include "physics/softness.h"

namespace zonesim::physics {

/// A rigid distance constraint between anchor points given in each body's local frame.
struct DistanceJoint {
  BodyIndex a = 0;
  BodyIndex b = kNoBody;
  Vec3 local_a = Vec3::Zero();
  Vec3 local_b = Vec3::Zero();  ///< A world point when b is kNoBody.
  double length = 1.0;
  double impulse = 0.0;  ///< Accumulated over the last step, for warm starting.
};

/// The distance joints of a world and their per-step solver rows.
class DistanceJoints {
 public:
  /// Adds a joint and returns its index.
  std::uint32_t add(const DistanceJoint& joint);
  /// The joints with their last impulses.
  std::span<const DistanceJoint> joints() const { return joints_; }
  /// Sets joint i's impulse, the next step's warm start (a joint carried from another world).
  void setImpulse(std::size_t i, double impulse) { joints_[i].impulse = impulse; }
  /// Builds the rows at the current positions; beta is the Baumgarte fraction per step.
  void prepare(const BodyStorage& bodies, double dt, double beta);
  /// Applies last step's impulses.
  void warmStart(BodyStorage& bodies);
  /// One Gauss-Seidel pass over the joints.
  void iterate(BodyStorage& bodies);
  /// Soft step, at each sub-step: fixes every joint's anchors, direction and effective mass at
  /// the bodies' motion so far (dp, dtheta) and applies the last sub-step's impulses.
  void prepareSoft(BodyStorage& bodies, std::span<const Vec3> dp, std::span<const Vec3> dtheta);
  /// Soft step: one pass over the joints, biased by the joint spring `soft`, or a relax pass
  /// without bias.
  void iterateSoft(BodyStorage& bodies, const Softness& soft, bool use_bias);

 private:
  using Row = JointRow;

  std::vector<DistanceJoint> joints_;
  std::vector<Row> rows_;
  // A joint as the soft step's sub-step sees it (bodies do not move within its passes).
  struct SoftRow {
    SoftAnchor a, b;
    Vec3 n;        // direction from a's anchor to b's
    double error;  // length minus the joint's length
    double mass;   // 1 / inverse mass along n
  };
  std::vector<SoftRow> soft_;
};

}  // namespace zonesim::physics
