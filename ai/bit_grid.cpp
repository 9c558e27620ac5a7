#include "ai/bit_grid.h"

#include "ai/grid_map.h"

namespace zonesim::ai {

BitGrid::BitGrid(const GridMap& map, bool transposed)
    : lines_(transposed ? map.width() : map.height()),
      length_(transposed ? map.height() : map.width()),
      // kPad blocked bits before the line, at least 64 after it, and one more word that a
      // window straddling the last one reads.
      stride_(std::size_t(kPad + length_ + 64 + 63) / 64 + 1),
      words_(std::size_t(lines_ + 2) * stride_, 0) {
  for (int line = 0; line < lines_; ++line) {
    for (int pos = 0; pos < length_; ++pos) {
      const bool open = transposed ? map.passable(line, pos) : map.passable(pos, line);
      const std::size_t bit = std::size_t(pos + kPad);
      if (open) words_[row(line) + bit / 64] |= std::uint64_t(1) << (bit % 64);
    }
  }
}

}  // namespace zonesim::ai
