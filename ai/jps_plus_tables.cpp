#include "ai/jps_plus_tables.h"

namespace zonesim::ai {

namespace {

constexpr int kDx[8] = {1, -1, 0, 0, 1, -1, 1, -1};
constexpr int kDy[8] = {0, 0, 1, -1, 1, 1, -1, -1};

}  // namespace

void JpsPlusTables::build(const BitGrid& rows) {
  const int w = rows.length(), h = rows.lines();
  width_ = w;
  auto walkable = [&](int x, int y) { return rows.walkable(y, x); };
  for (auto& table : table_) table.assign(std::size_t(w + 2) * std::size_t(h + 2), 0);
  // Does entering (x, y) moving straight along (dx, dy) make it a jump point (a forced
  // neighbour, as in BitGrid::scanUp)?
  auto forced = [&](int x, int y, int dx, int dy) {
    if (dx != 0) {
      return (walkable(x, y - 1) && !walkable(x - dx, y - 1)) ||
             (walkable(x, y + 1) && !walkable(x - dx, y + 1));
    }
    return (walkable(x - 1, y) && !walkable(x - 1, y - dy)) ||
           (walkable(x + 1, y) && !walkable(x + 1, y - dy));
  };
  // One step further than the next cell's value: towards its jump point or its wall.
  auto further = [](std::int32_t next) { return next > 0 ? next + 1 : next - 1; };
  // Straight directions, each scanned so that the next cell along it is done first.
  for (int d = 0; d < 4; ++d) {
    const int dx = kDx[d], dy = kDy[d];
    std::vector<std::int32_t>& t = table_[d];
    for (int i = 0; i < w * h; ++i) {
      // Walk rows (or columns) against the direction.
      const int y = dy > 0 ? h - 1 - i / w : i / w;
      const int x = dx > 0 ? w - 1 - i % w : i % w;
      if (!walkable(x, y)) continue;
      const int nx = x + dx, ny = y + dy;
      if (!walkable(nx, ny)) {
        t[padded(x, y)] = 0;
      } else {
        t[padded(x, y)] = forced(nx, ny, dx, dy) ? 1 : further(t[padded(nx, ny)]);
      }
    }
  }
  // Diagonals: the next cell is one row further along dy, so rows go against dy.
  for (int d = 4; d < 8; ++d) {
    const int dx = kDx[d], dy = kDy[d];
    const int along_x = direction(dx, 0), along_y = direction(0, dy);
    std::vector<std::int32_t>& t = table_[d];
    for (int r = 0; r < h; ++r) {
      const int y = dy > 0 ? h - 1 - r : r;
      for (int x = 0; x < w; ++x) {
        if (!walkable(x, y)) continue;
        const int nx = x + dx, ny = y + dy;
        if (!walkable(x + dx, y) || !walkable(x, y + dy) || !walkable(nx, ny)) {
          t[padded(x, y)] = 0;
        } else if (table_[along_x][padded(nx, ny)] > 0 || table_[along_y][padded(nx, ny)] > 0) {
          t[padded(x, y)] = 1;
        } else {
          t[padded(x, y)] = further(t[padded(nx, ny)]);
        }
      }
    }
  }
}

}  // namespace zonesim::ai
