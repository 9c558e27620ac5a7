#pragma once
// A 2D grid of passable and blocked cells, loaded from the Moving AI .map format.

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "ai/octile.h"

namespace zonesim::ai {

/// Row-major grid of passable flags; every change bumps version() so caches can notice.
class GridMap {
 public:
  /// An empty 0x0 map.
  GridMap() = default;
  /// A width x height map, every cell passable.
  GridMap(int width, int height);

  /// Number of columns.
  int width() const { return width_; }
  /// Number of rows.
  int height() const { return height_; }
  /// Row-major index of a cell.
  int index(int x, int y) const { return y * width_ + x; }
  /// Cell at a row-major index.
  Cell cellAt(int idx) const { return Cell{idx % width_, idx / width_}; }
  /// True when (x, y) lies on the map.
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  /// True when (x, y) is on the map and walkable.
  bool passable(int x, int y) const { return inside(x, y) && cells_[index(x, y)] != 0; }
  /// Walkable flag by row-major index (no bounds check: the hot path of the searches).
  bool passableAt(int idx) const { return cells_[idx] != 0; }
  /// Opens or closes a cell (a door); bumps version() when the flag changes.
  void setPassable(int x, int y, bool open);
  /// Incremented by every change to the cells.
  std::uint64_t version() const { return version_; }
  /// Number of walkable cells.
  int passableCount() const;

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> cells_;
  std::uint64_t version_ = 0;
};

/// Parses a Moving AI .map; throws ParseError naming `file` and the line.
GridMap parseMovingAiMap(std::istream& in, const std::string& file);
/// Reads a Moving AI .map file; throws ParseError (line 0 when it cannot be opened).
GridMap loadMovingAiMap(const std::string& path);

}  // namespace zonesim::ai
