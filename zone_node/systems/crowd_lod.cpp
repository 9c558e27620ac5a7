#include "zone_node/systems/crowd_lod.h"

namespace zonesim::zone {

crowd::LodSettings lodOf(const CrowdLod& l) {
  crowd::LodSettings s;
  s.near_radius = l.near_radius;
  s.far_radius = l.far_radius;
  s.mid_every = l.mid_every;
  s.far_every = l.far_every;
  s.mid_steers = l.mid_steers;
  s.far_steers = l.far_steers;
  s.crowded_count = l.crowded_count;
  s.crowded_cell = l.crowded_cell;
  return s;
}

}  // namespace zonesim::zone
