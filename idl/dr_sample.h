#pragma once
// The dead-reckoning fields of a DDS EntityUpdate: the model byte (order in bits 0-1, rotating
// in bit 2, smallest-three index in bits 3-4) and the conversion to the codec's WireEntity.

#include <cstdint>

#include "dr/dr_model.h"
#include "dr/state_codec.h"
#include "zonesim.h"

namespace zonesim::dds {

/// The model byte of an EntityUpdate.
inline std::uint8_t packModel(const dr::Model& m, int rot_largest) {
  int largest = rot_largest >= 0 && rot_largest < 4 ? rot_largest : 0;
  return std::uint8_t(int(m.order) | (m.spin == dr::Spin::Rotating ? 4 : 0) | (largest << 3));
}

/// The model an EntityUpdate was sent with (an order of 3 reads as second).
inline dr::Model unpackModel(std::uint8_t b) {
  int order = b & 3;
  return {dr::Order(order > 2 ? 2 : order), (b & 4) != 0 ? dr::Spin::Rotating : dr::Spin::Fixed};
}

/// The codec's view of a sample sampled at `tick` relative to `cell`.
inline dr::WireEntity toWireEntity(const zonesim_dds_EntityUpdate& u, std::uint64_t tick,
                                   int cell) {
  dr::WireEntity e;
  e.id = u.id;
  e.kind = u.kind;
  e.tick = tick;
  e.cell = cell;
  e.model = unpackModel(u.model);
  e.rot_largest = (u.model >> 3) & 3;
  e.state.pos = {u.pos.x, u.pos.y, u.pos.z};
  e.state.vel = {u.vel.x, u.vel.y, u.vel.z};
  e.state.acc = {u.acc.x, u.acc.y, u.acc.z};
  e.state.rot = {u.rot.x, u.rot.y, u.rot.z, u.rot.w};
  e.state.angvel = {u.angvel.x, u.angvel.y, u.angvel.z};
  return e;
}

}  // namespace zonesim::dds
