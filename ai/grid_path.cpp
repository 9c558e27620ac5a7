#include "ai/grid_path.h"

#include <cstdlib>

#include "ai/grid_map.h"

namespace zonesim::ai {

double pathLength(const std::vector<Cell>& cells) {
  double len = 0.0;
  for (std::size_t i = 1; i < cells.size(); ++i) {
    bool diagonal = cells[i].x != cells[i - 1].x && cells[i].y != cells[i - 1].y;
    len += diagonal ? kDiagonalCost : 1.0;
  }
  return len;
}

bool isValidPath(const GridMap& map, const std::vector<Cell>& cells) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (!map.passable(cells[i].x, cells[i].y)) return false;
    if (i == 0) continue;
    int dx = cells[i].x - cells[i - 1].x, dy = cells[i].y - cells[i - 1].y;
    if (std::abs(dx) > 1 || std::abs(dy) > 1 || (dx == 0 && dy == 0)) return false;
    if (dx != 0 && dy != 0) {
      // No corner cutting: both cardinal cells beside a diagonal step must be free.
      if (!map.passable(cells[i - 1].x + dx, cells[i - 1].y) ||
          !map.passable(cells[i - 1].x, cells[i - 1].y + dy)) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace zonesim::ai
