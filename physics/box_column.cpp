#include "physics/box_column.h"

#include <algorithm>
#include <cmath>

namespace zonesim::physics {

BoxColumn::BoxColumn(const WorldSettings& settings, std::span<const double> densities)
    : world_(settings) {
  BodyDesc floor;
  floor.type = BodyType::Static;
  floor.shape = Shape::box(Vec3(50, 1, 50));
  floor.position = Vec3(0, -1, 0);
  world_.addBody(floor);
  for (std::size_t k = 0; k < densities.size(); ++k) {
    BodyDesc box;
    box.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
    box.position = Vec3(0, 0.5 + static_cast<double>(k), 0);
    box.friction = 0.5;
    box.density = densities[k];
    world_.addBody(box);
    start_.push_back(box.position);
  }
}

void BoxColumn::run(double seconds) {
  const int steps = static_cast<int>(std::lround(seconds * 60.0));
  for (int s = 0; s < steps; ++s) world_.step(1.0 / 60.0);
}

BoxColumn::Drift BoxColumn::drift() const {
  Drift d;
  for (std::size_t k = 0; k < start_.size(); ++k) {
    const Vec3 v = world_.bodies().position[k + 1] - start_[k];
    d.horizontal = std::max(d.horizontal, std::hypot(v.x(), v.z()));
    d.vertical = std::max(d.vertical, std::abs(v.y()));
    d.total = std::max(d.total, v.norm());
  }
  return d;
}

double BoxColumn::topHeight() const {
  return world_.bodies().position[start_.size()].y();
}

}  // namespace zonesim::physics
