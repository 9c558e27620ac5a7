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

BitGrid::Stop BitGrid::scanUp(int line, int pos) const {
  // Bit i of each window is position pos + i. A side cell is forced when it is walkable and
  // the one behind it (bit i - 1) is blocked; bit 0, the cell scanned from, is never a stop,
  // so each window advances by 63.
  for (;;) {
    const std::uint64_t here = window(line, pos);
    const std::uint64_t left = window(line - 1, pos), right = window(line + 1, pos);
    const std::uint64_t forced = (left & ~(left << 1)) | (right & ~(right << 1));
    const std::uint64_t stop = (~here | forced) & ~std::uint64_t(1);
    if (stop != 0) {
      const int i = __builtin_ctzll(stop);
      return Stop{pos + i, ((here >> i) & 1) != 0};
    }
    pos += 63;
  }
}

BitGrid::Stop BitGrid::scanDown(int line, int pos) const {
  // Mirror of scanUp: bit 63 is the cell scanned from, bit i is position pos - 63 + i, and the
  // cell behind a side cell is bit i + 1.
  for (;;) {
    const int base = pos - 63;
    const std::uint64_t here = window(line, base);
    const std::uint64_t left = window(line - 1, base), right = window(line + 1, base);
    const std::uint64_t forced = (left & ~(left >> 1)) | (right & ~(right >> 1));
    const std::uint64_t stop = (~here | forced) & ~(std::uint64_t(1) << 63);
    if (stop != 0) {
      const int i = 63 - __builtin_clzll(stop);
      return Stop{base + i, ((here >> i) & 1) != 0};
    }
    pos -= 63;
  }
}

}  // namespace zonesim::ai
