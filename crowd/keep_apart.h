#pragma once
// Bodies that do not pass through each other, decided by each agent alone: every agent moves
// at most half the gap toward each neighbour (the gap taken at the start of the step, as every
// rank sees it). Since the true distance after a step is at least its projection on the line
// between the two start points, d' >= d - gap / 2 - gap / 2 = 2 radius: no step makes a new
// overlap, whatever the neighbour does, as long as it keeps the same rule. An overlap that is
// already there (a random placement) asks each of the two to back off by half its depth (at
// most its reach a step); where an agent cannot do that and keep its other gaps (squeezed), it
// keeps every gap and backs off where it can, so an overlap never deepens. The rule needs no
// exchange beyond the positions at the start of the step, so it is exact across zones.
//
// Per agent this is a small linear program in the plane: the displacement closest to the one
// the steering wants, inside the half-planes {x : x . n <= c} of its neighbours and a disc
// (the most it may move), solved incrementally (each new half-plane the point violates puts
// the optimum on its line).

#include <cstddef>
#include <span>
#include <vector>

#include "crowd/neighbour_grid.h"
#include "crowd/vec2.h"

namespace zonesim::crowd {

/// One neighbour's limit on a displacement x: x . normal <= offset.
struct GapPlane {
  Vec2 normal;    ///< unit vector from the agent toward the neighbour
  double offset;  ///< half the gap between the two bodies (negative when they overlap)
};

/// The half-planes of an agent's neighbours, gathered once per agent and solved.
class KeepApart {
 public:
  /// Starts an agent: `radius` of every body, `reach` the most it may move this step.
  void begin(double radius, double reach) {
    radius_ = radius;
    reach_ = reach;
    planes_.clear();
  }
  /// A neighbour `rel` (its position minus the agent's) away; `self_first` breaks the tie of
  /// two agents at the same point (which of the two backs off toward -x). Neighbours whose
  /// gap is more than twice the reach cannot bind and are not kept.
  void neighbour(Vec2 rel, bool self_first);
  /// How far a neighbour may be and still bind: 2 radius + 2 reach, the query radius.
  double queryRadius() const { return 2.0 * (radius_ + reach_); }
  /// The neighbours gathered so far.
  std::span<const GapPlane> planes() const { return planes_; }

  /// The displacement closest to `wish` that keeps every gap and the reach. Where the
  /// overlaps cannot all be backed off by half their depth, each is asked for no more than
  /// the reach; where not even that fits, the closest that keeps every gap and deepens no
  /// overlap (half-planes through the origin for those).
  Vec2 solve(Vec2 wish) const;
  /// The move an agent makes: solve(wish), or, where a gap holds it back, solved again with
  /// a sidestep to its right (three times as far as ahead, about 72 degrees, within the
  /// reach). Two agents meeting head-on both step aside, so they pass instead of pressing on
  /// the line between them for ever, and opposing flows in a doorway form lanes.
  Vec2 move(Vec2 wish) const;
  /// True when `x` keeps every gap and deepens no overlap (up to rounding of 1e-12 m).
  bool keeps(Vec2 x) const;

 private:
  double radius_ = 0.0, reach_ = 0.0;
  std::vector<GapPlane> planes_;
};

/// Gathers into `k` (begun) the neighbours of the grid's entry `self` that may bind it, in the
/// grid's canonical order.
void gatherGaps(const NeighbourGrid& grid, std::int32_t self, KeepApart& k);

}  // namespace zonesim::crowd
