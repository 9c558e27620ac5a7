#pragma once
// The walkable flags of a map packed 64 cells to a word, for jump point search's straight jumps
// (Harabor and Grastien's block-based scan): one step reads 55 cells of its line and of the two
// lines beside it at once and finds the first blocked cell or forced neighbour with one bit
// count. A transposed copy (lines = columns) serves vertical jumps with the same code.

#include <cstdint>
#include <cstring>
#include <vector>

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "BitGrid reads its words as bytes");

namespace zonesim::ai {

class GridMap;

/// Walkable bits by line (a row, or a column when transposed), outside the map blocked.
class BitGrid {
 public:
  /// Where a straight scan stops: at a jump point, or before a blocked cell.
  struct Stop {
    int at;     ///< position of the jump point, or of the first blocked cell
    bool jump;  ///< true: `at` is a jump point (walkable, with a forced neighbour)
    /// For a jump point that is a bend (blocked ahead, exactly one side line open there, so
    /// its corner behind is blocked): that side, -1 (line - 1) or +1; else 0.
    int turn;
  };

  /// An empty grid (no lines).
  BitGrid() = default;
  /// Packs `map`'s rows, or its columns when `transposed`.
  BitGrid(const GridMap& map, bool transposed);

  /// True when cell `pos` of `line` is walkable; any line in [-1, lines()] and position in
  /// [-1, length()] may be asked (outside the map is blocked).
  bool walkable(int line, int pos) const {
    const std::size_t bit = std::size_t(pos + kPad);
    return (words_[row(line) + bit / 64] >> (bit % 64)) & 1;
  }
  /// Scans from `pos` (walkable) towards higher positions along `line`: the first cell with a
  /// forced neighbour (a walkable cell on a side line whose cell behind is blocked), or the
  /// first blocked cell; says whether a jump point found is a bend.
  Stop scanUp(int line, int pos) const;
  /// As scanUp, towards lower positions.
  Stop scanDown(int line, int pos) const;
  /// Number of lines (rows, or columns when transposed).
  int lines() const { return lines_; }
  /// Cells per line.
  int length() const { return length_; }

 private:
  // Positions are stored kPad bits in, so that a 64-bit window around any position in
  // [-1, length] stays inside the line and reads blocked padding beyond the map.
  static constexpr int kPad = 64;
  // A scan reads 8 unaligned bytes per line and step; shifted into place, 57 of their bits are
  // always valid: the cell scanned from, kWindow more, and the cell ahead of the last (a
  // stop's, read for bends).
  static constexpr int kWindow = 55;
  static constexpr std::uint64_t kUpValid = ((std::uint64_t(1) << kWindow) - 1) << 1;  // 1..55
  static constexpr std::uint64_t kDownValid = kUpValid << 7;                           // 8..62
  /// Stop at bit i of the windows (the cell ahead at bit i + ahead).
  static Stop stopAt(int at, int i, int ahead, std::uint64_t here, std::uint64_t left,
                     std::uint64_t right) {
    if (((here >> i) & 1) == 0) return Stop{at, false, 0};
    const bool l = (left >> i) & 1, r = (right >> i) & 1;
    const bool bend = ((here >> (i + ahead)) & 1) == 0 && l != r;
    return Stop{at, true, bend ? (l ? -1 : 1) : 0};
  }
  std::size_t row(int line) const { return std::size_t(line + 1) * stride_; }
  const unsigned char* lineBytes(int line) const {
    return reinterpret_cast<const unsigned char*>(words_.data() + row(line));
  }
  /// 8 bytes from `p`, the first the lowest (the bit order of the words on a little-endian
  /// machine).
  static std::uint64_t load(const unsigned char* p) {
    std::uint64_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }

  int lines_ = 0, length_ = 0;
  std::size_t stride_ = 0;            // words per line, padding included
  std::vector<std::uint64_t> words_;  // lines -1 .. lines_, each stride_ words
};

// Inline: a jump point search calls these at every diagonal step.
inline BitGrid::Stop BitGrid::scanUp(int line, int pos) const {
  // Each window is 8 bytes read from the byte holding `pos`, shifted so that bit i is position
  // pos + i; bits 0..56 are always valid. A side cell is forced when it is walkable and the one
  // behind it (bit i - 1) is blocked; bit 0, the cell scanned from, is never a stop.
  const unsigned char* here_line = lineBytes(line);
  const std::size_t stride = stride_ * 8;
  for (;;) {
    const std::size_t bit = std::size_t(pos + kPad), byte = bit / 8;
    const unsigned s = bit % 8;
    const std::uint64_t here = load(here_line + byte) >> s;
    const std::uint64_t left = load(here_line - stride + byte) >> s;
    const std::uint64_t right = load(here_line + stride + byte) >> s;
    const std::uint64_t forced = (left & ~(left << 1)) | (right & ~(right << 1));
    const std::uint64_t stop = (~here | forced) & kUpValid;
    if (stop != 0) {
      const int i = __builtin_ctzll(stop);
      return stopAt(pos + i, i, 1, here, left, right);
    }
    pos += kWindow;
  }
}

inline BitGrid::Stop BitGrid::scanDown(int line, int pos) const {
  // Mirror of scanUp: the window is shifted up so that `pos` is bit 63 and bit i is position
  // pos - 63 + i (bits 7..63 valid); the cell behind a side cell is bit i + 1.
  const unsigned char* here_line = lineBytes(line);
  const std::size_t stride = stride_ * 8;
  for (;;) {
    const std::size_t bit = std::size_t(pos + kPad), byte = (bit - 56) / 8;
    const unsigned s = unsigned(63 - (bit - byte * 8));
    const std::uint64_t here = load(here_line + byte) << s;
    const std::uint64_t left = load(here_line - stride + byte) << s;
    const std::uint64_t right = load(here_line + stride + byte) << s;
    const std::uint64_t forced = (left & ~(left >> 1)) | (right & ~(right >> 1));
    const std::uint64_t stop = (~here | forced) & kDownValid;
    if (stop != 0) {
      const int i = 63 - __builtin_clzll(stop);
      return stopAt(pos - 63 + i, i, -1, here, left, right);
    }
    pos -= kWindow;
  }
}

}  // namespace zonesim::ai
