#pragma once
// States for the wire tests: the default codec's 1000 m world, first order, each state already
// through the codec once, so a round trip must give back the very same floats.

#include "dr/state_codec.h"

namespace zonesim::gateway::testing {

/// The codec of default CodecParams.
inline const dr::StateCodec& codec() {
  static const dr::StateCodec c{dr::CodecParams{}};
  return c;
}

/// An entity at (x, 0, 1000 - x), sampled at tick 9, moving at (1, 0, 2).
inline dr::WireEntity state(std::uint64_t id, float x) {
  dr::WireEntity e;
  e.id = id;
  e.tick = 9;
  e.state.pos = {x, 0, 1000 - x};
  e.state.vel = {1, 0, 2};
  e.cell = codec().columns() * int((1000 - x) / 50 < 19 ? (1000 - x) / 50 : 19) +
           int(x / 50 < 19 ? x / 50 : 19);
  e.state = codec().roundTrip(e.state, e.model, e.cell);
  return e;
}

}  // namespace zonesim::gateway::testing
