// BitGrid's many-cells-at-a-time straight scans against a cell-by-cell scan of the same rule, on
// random maps whose lines are shorter and longer than a word, rows and transposed columns.

#include "ai/bit_grid.h"

#include <gtest/gtest.h>

#include "tests/ai/reference_dijkstra.h"

namespace zonesim::ai {
namespace {

/// The scan done one cell at a time: the first position after `pos` (stepping by `dir`) that
/// is blocked or has a forced neighbour on a side line, and whether that jump point is a bend
/// (blocked ahead, one side open).
BitGrid::Stop scanCellByCell(const GridMap& m, bool transposed, int line, int pos, int dir) {
  auto open = [&](int l, int p) { return transposed ? m.passable(l, p) : m.passable(p, l); };
  for (;;) {
    pos += dir;
    if (!open(line, pos)) return BitGrid::Stop{pos, false, 0};
    bool forced = false;
    for (int side : {-1, 1})
      forced = forced || (open(line + side, pos) && !open(line + side, pos - dir));
    if (!forced) continue;
    const bool before = open(line - 1, pos), after = open(line + 1, pos);
    const bool bend = !open(line, pos + dir) && before != after;
    return BitGrid::Stop{pos, true, bend ? (before ? -1 : 1) : 0};
  }
}

TEST(BitGridTest, ScansMatchACellByCellScanOnRandomMaps) {
  int jumps = 0, walls = 0, bends = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    // Widths below, at and well above one word; densities from open to cluttered.
    const int w = 20 + int(seed * 37 % 200), h = 10 + int(seed * 53 % 150);
    GridMap m = test::randomMap(w, h, 0.02 * double(seed % 6), seed);
    for (bool transposed : {false, true}) {
      BitGrid bits(m, transposed);
      ASSERT_EQ(bits.lines(), transposed ? w : h);
      ASSERT_EQ(bits.length(), transposed ? h : w);
      for (int line = 0; line < bits.lines(); ++line) {
        for (int pos = 0; pos < bits.length(); ++pos) {
          const bool open = transposed ? m.passable(line, pos) : m.passable(pos, line);
          ASSERT_EQ(bits.walkable(line, pos), open);
          if (!open) continue;
          for (int dir : {1, -1}) {
            const BitGrid::Stop want = scanCellByCell(m, transposed, line, pos, dir);
            const BitGrid::Stop got = dir > 0 ? bits.scanUp(line, pos) : bits.scanDown(line, pos);
            ASSERT_EQ(got.at, want.at) << "seed " << seed << " line " << line << " pos " << pos;
            ASSERT_EQ(got.jump, want.jump) << "seed " << seed << " line " << line << " pos " << pos;
            ASSERT_EQ(got.turn, want.turn) << "seed " << seed << " line " << line << " pos " << pos;
            ++(want.jump ? jumps : walls);
            bends += want.turn != 0;
          }
        }
      }
    }
  }
  EXPECT_GT(jumps, 1000);
  EXPECT_GT(walls, 1000);
  EXPECT_GT(bends, 100);
}

TEST(BitGridTest, OutsideTheMapIsBlocked) {
  GridMap m(70, 3);  // all open: scans run to the border, across a word boundary
  BitGrid bits(m, false);
  EXPECT_FALSE(bits.walkable(-1, 5));
  EXPECT_FALSE(bits.walkable(3, 5));
  EXPECT_FALSE(bits.walkable(1, -1));
  EXPECT_FALSE(bits.walkable(1, 70));
  EXPECT_EQ(bits.scanUp(1, 0).at, 70);
  EXPECT_FALSE(bits.scanUp(1, 0).jump);
  EXPECT_EQ(bits.scanDown(1, 69).at, -1);
  EXPECT_FALSE(bits.scanDown(1, 69).jump);
}

}  // namespace
}  // namespace zonesim::ai
