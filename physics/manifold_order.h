#pragma once
// The order of a manifold's points. The solvers visit them in order and the first takes the
// most of the load, so a rocking box's sinking side must come first: points kept in the order
// the narrowphase found them (a face's clipped polygon, or the ride of a recycled manifold)
// let stacks rock and walk (docs/physics.md, "Contact points deepest first").

#include <utility>

#include "physics/contact.h"

namespace zonesim::physics {

/// Puts the manifold's points deepest first, stable among equal depths, calling
/// also_swap(k) each time points k - 1 and k trade places, so that data kept beside the
/// points (a recycled manifold's origins and impulses) follows them. Insertion sort of at most
/// four points: no work when already in order.
template <class AlsoSwap>
void sortDeepestFirst(Manifold& m, AlsoSwap&& also_swap) {
  for (int i = 1; i < m.count; ++i) {
    for (int k = i; k > 0 && m.points[k].depth > m.points[k - 1].depth; --k) {
      std::swap(m.points[k], m.points[k - 1]);
      also_swap(k);
    }
  }
}

}  // namespace zonesim::physics
