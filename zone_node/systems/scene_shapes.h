#pragma once
// The engine shapes of the scene's named bodies (physics.bodies): set pieces place them as
// given; a dynamic compound is moved to its centre of mass, which its entity then sits at.

#include "common/math.h"
#include "common/scene_geometry.h"
#include "physics/compound.h"

namespace zonesim {
struct SceneBody;
}  // namespace zonesim

namespace zonesim::zone {

/// A scene vector as the engine's.
inline Vec3 toVec3(const SceneVec3& v) {
  return Vec3(v.x, v.y, v.z);
}

/// A scene rotation as the engine's.
inline Quat toQuat(const SceneQuat& q) {
  return Quat(q.w, q.x, q.y, q.z);
}

/// The body's shape in its scene frame: a compound's parts where the scene puts them.
physics::Shape sceneShape(const SceneBody& b);

/// A compound body's shape centred on its parts' centre of mass (physics::centreCompound),
/// and that centre in the body's frame.
physics::CentredCompound centredSceneCompound(const SceneBody& b);

/// Where a named body's engine body starts: its scene position, or for a dynamic compound the
/// centre of mass of its parts placed there (set pieces are placed as given).
Vec3 entityStart(const SceneBody& b);

}  // namespace zonesim::zone
