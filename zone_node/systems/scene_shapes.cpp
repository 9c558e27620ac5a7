#include "zone_node/systems/scene_shapes.h"

#include <vector>

#include "common/scene_physics.h"

namespace zonesim::zone {

namespace {

/// A sphere, box or capsule sized as the scene sizes them (full box edges, capsule length).
template <class Sized>
physics::Shape primitive(const Sized& b) {
  switch (b.shape) {
    case SceneBody::Shape::Box:
      return physics::Shape::box(toVec3(b.size) * 0.5);
    case SceneBody::Shape::Capsule:
      return physics::Shape::capsule(b.radius, 0.5 * b.length);
    default:
      return physics::Shape::sphere(b.radius);
  }
}

std::vector<physics::ShapePart> partsOf(const SceneBody& b) {
  std::vector<physics::ShapePart> parts;
  for (const SceneBody::Part& p : b.parts)
    parts.push_back(physics::ShapePart{primitive(p), toVec3(p.position), toQuat(p.orientation)});
  return parts;
}

}  // namespace

physics::Shape sceneShape(const SceneBody& b) {
  if (b.shape == SceneBody::Shape::Compound) return physics::makeCompound(partsOf(b));
  return primitive(b);
}

physics::CentredCompound centredSceneCompound(const SceneBody& b) {
  return physics::centreCompound(partsOf(b));
}

Vec3 entityStart(const SceneBody& b) {
  if (b.shape != SceneBody::Shape::Compound || b.motion != SceneBody::Motion::Dynamic)
    return toVec3(b.position);
  return toVec3(b.position) + toQuat(b.orientation) * centredSceneCompound(b).centre;
}

}  // namespace zonesim::zone
