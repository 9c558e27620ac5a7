#pragma once
// The walkable flags of a map packed 64 cells to a word, for jump point search's straight jumps
// (Harabor and Grastien's block-based scan): one jump reads 64 cells of its line and of the two
// lines beside it at once and finds the first blocked cell or forced neighbour with one bit
// count. A transposed copy (lines = columns) serves vertical jumps with the same code.

#include <cstdint>
#include <vector>

namespace zonesim::ai {

class GridMap;

/// Walkable bits by line (a row, or a column when transposed), outside the map blocked.
class BitGrid {
 public:
  /// Where a straight scan stops: at a jump point, or before a blocked cell.
  struct Stop {
    int at;     ///< position of the jump point, or of the first blocked cell
    bool jump;  ///< true: `at` is a jump point (walkable, with a forced neighbour)
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
  /// first blocked cell.
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
  std::size_t row(int line) const { return std::size_t(line + 1) * stride_; }
  /// 64 bits of `line` from position `pos` up (bit 0 = pos).
  std::uint64_t window(int line, int pos) const {
    const std::size_t bit = std::size_t(pos + kPad), w = row(line) + bit / 64;
    const unsigned s = bit % 64;
    return s == 0 ? words_[w] : (words_[w] >> s) | (words_[w + 1] << (64 - s));
  }

  int lines_ = 0, length_ = 0;
  std::size_t stride_ = 0;            // words per line, padding included
  std::vector<std::uint64_t> words_;  // lines -1 .. lines_, each stride_ words
};

}  // namespace zonesim::ai
