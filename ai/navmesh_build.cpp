#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "ai/navmesh.h"

namespace zonesim::ai {

namespace {

// Distance between the squares of two cells `dx`, `dy` apart.
double squareGap(int dx, int dy) {
  double gx = std::max(0, std::abs(dx) - 1), gy = std::max(0, std::abs(dy) - 1);
  return std::hypot(gx, gy);
}

void checkRadius(double radius) {
  if (!std::isfinite(radius) || radius < 0)
    throw std::invalid_argument("navmesh: agent_radius " + std::to_string(radius) +
                                " must be finite and >= 0");
}

}  // namespace

std::vector<std::uint8_t> erodeWalkable(const GridMap& map, double radius) {
  checkRadius(radius);
  const int w = map.width(), h = map.height();
  std::vector<std::uint8_t> open(std::size_t(w) * std::size_t(h), 0);
  for (int i = 0; i < w * h; ++i) open[std::size_t(i)] = map.passableAt(i) ? 1 : 0;
  if (radius == 0) return open;
  // Offsets of the cells whose squares come closer than `radius` to a blocked square.
  const int reach = int(std::ceil(radius)) + 1;
  std::vector<Cell> near;
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx)
      if (squareGap(dx, dy) < radius) near.push_back(Cell{dx, dy});
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // The map's edge is a wall: the gap to it is the number of cells in between.
      if (std::min({x, y, w - 1 - x, h - 1 - y}) < radius) open[std::size_t(map.index(x, y))] = 0;
      if (map.passable(x, y)) continue;
      for (Cell d : near)
        if (map.inside(x + d.x, y + d.y)) open[std::size_t(map.index(x + d.x, y + d.y))] = 0;
    }
  }
  return open;
}

void closeBoxes(GridMap& map, const std::vector<NavBox>& boxes) {
  for (const NavBox& b : boxes) {
    // Cells whose open square meets the box's interior: x in (floor(x0), ceil(x1)).
    const int cx0 = std::max(0, int(std::floor(b.x0))),
              cx1 = std::min(map.width(), int(std::ceil(b.x1)));
    const int cy0 = std::max(0, int(std::floor(b.y0))),
              cy1 = std::min(map.height(), int(std::ceil(b.y1)));
    if (!(b.x1 > b.x0 && b.y1 > b.y0)) continue;  // no area
    for (int y = cy0; y < cy1; ++y)
      for (int x = cx0; x < cx1; ++x) map.setPassable(x, y, false);
  }
}

NavMesh::NavMesh(const GridMap& map, const NavMeshConfig& config) : config_(config) {
  checkRadius(config.agent_radius);
  build(map);
}

NavMesh::NavMesh(const GridMap& map, const std::vector<NavBox>& boxes, const NavMeshConfig& config)
    : config_(config) {
  checkRadius(config.agent_radius);
  GridMap closed = map;
  closeBoxes(closed, boxes);
  build(closed);
}

void NavMesh::build(const GridMap& map) {
  width_ = map.width();
  height_ = map.height();
  const std::vector<std::uint8_t> open = erodeWalkable(map, config_.agent_radius);
  cell_polygon_.assign(open.size(), -1);
  auto free = [&](int x, int y) {
    std::size_t i = std::size_t(y) * std::size_t(width_) + std::size_t(x);
    return open[i] != 0 && cell_polygon_[i] < 0;
  };
  // Greedy rectangles: from each unassigned cell in row-major order, the longest free run to
  // the right, then every following row where that whole run is free.
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      if (!free(x, y)) continue;
      NavPolygon r{x, y, x + 1, y + 1};
      while (r.x1 < width_ && free(r.x1, y)) ++r.x1;
      auto rowFree = [&](int row) {
        for (int cx = r.x0; cx < r.x1; ++cx)
          if (!free(cx, row)) return false;
        return true;
      };
      while (r.y1 < height_ && rowFree(r.y1)) ++r.y1;
      const std::int32_t id = std::int32_t(polygons_.size());
      for (int cy = r.y0; cy < r.y1; ++cy)
        for (int cx = r.x0; cx < r.x1; ++cx)
          cell_polygon_[std::size_t(cy) * std::size_t(width_) + std::size_t(cx)] = id;
      polygons_.push_back(r);
    }
  }
  // Portals along each polygon's right and bottom edges (the others are its neighbours').
  for (std::int32_t p = 0; p < std::int32_t(polygons_.size()); ++p) {
    const NavPolygon r = polygons_[std::size_t(p)];
    auto scan = [&](bool vertical) {
      const int across = vertical ? r.x1 : r.y1;
      if (across >= (vertical ? width_ : height_)) return;
      const int from = vertical ? r.y0 : r.x0, to = vertical ? r.y1 : r.x1;
      int run = from;
      for (int k = from; k <= to; ++k) {
        std::int32_t q = -1, prev = -1;
        if (k < to) q = vertical ? polygonAt(across, k) : polygonAt(k, across);
        if (k > from) prev = vertical ? polygonAt(across, k - 1) : polygonAt(k - 1, across);
        if (k > from && q != prev) {
          if (prev >= 0) {
            NavPortal portal = vertical ? NavPortal{across, run, across, k, p, prev}
                                        : NavPortal{run, across, k, across, p, prev};
            portals_.push_back(portal);
          }
          run = k;
        }
      }
    };
    scan(true);
    scan(false);
  }
  offsets_.assign(polygons_.size() + 1, 0);
  for (const NavPortal& portal : portals_) {
    ++offsets_[std::size_t(portal.low) + 1];
    ++offsets_[std::size_t(portal.high) + 1];
  }
  for (std::size_t p = 0; p < polygons_.size(); ++p) offsets_[p + 1] += offsets_[p];
  adjacency_.assign(std::size_t(offsets_.back()), -1);
  std::vector<std::int32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (std::int32_t i = 0; i < std::int32_t(portals_.size()); ++i) {
    adjacency_[std::size_t(fill[std::size_t(portals_[std::size_t(i)].low)]++)] = i;
    adjacency_[std::size_t(fill[std::size_t(portals_[std::size_t(i)].high)]++)] = i;
  }
  polygons_.shrink_to_fit();
  portals_.shrink_to_fit();
}

int NavMesh::polygonAt(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return -1;
  return cell_polygon_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
}

int NavMesh::polygonAt(Vec2 p) const {
  // Checked in doubles first: a far point must not overflow the int conversion.
  if (!(p.x >= 0 && p.y >= 0 && p.x < width_ && p.y < height_)) return -1;
  return polygonAt(int(std::floor(p.x)), int(std::floor(p.y)));
}

std::size_t NavMesh::memoryBytes() const {
  return polygons_.capacity() * sizeof(NavPolygon) + portals_.capacity() * sizeof(NavPortal) +
         offsets_.capacity() * sizeof(std::int32_t) + adjacency_.capacity() * sizeof(std::int32_t) +
         cell_polygon_.capacity() * sizeof(std::int32_t);
}

}  // namespace zonesim::ai
