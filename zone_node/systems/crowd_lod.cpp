#include "zone_node/systems/crowd_lod.h"

namespace zonesim::zone {

crowd::LodSettings lodOf(const CrowdLod& l) {
  crowd::LodSettings s;
  s.nearRadius = l.near_radius;
  s.farRadius = l.far_radius;
  s.midEvery = l.mid_every;
  s.farEvery = l.far_every;
  s.midSteers = l.mid_steers;
  s.farSteers = l.far_steers;
  return s;
}

}  // namespace zonesim::zone
