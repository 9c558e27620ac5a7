// InterestGrid: cell numbering, clamping of points outside the world, and cellsWithin()
// against a brute-force check of every cell.

#include "common/interest_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace zonesim {
namespace {

SceneBox box(double x0, double z0, double x1, double z1) {
  return SceneBox{{x0, 0, z0}, {x1, 10, z1}};
}

TEST(InterestGrid, SizeRoundsUpToWholeCells) {
  InterestGrid grid(box(-100, 0, 100, 130), 50);
  EXPECT_EQ(grid.columns(), 4);
  EXPECT_EQ(grid.rows(), 3);  // 130 m needs a third, partial row
  EXPECT_EQ(grid.cellCount(), 12);
  EXPECT_EQ(grid.cell_size(), 50);
}

TEST(InterestGrid, CellOfNumbersRowMajorFromTheMinCorner) {
  InterestGrid grid(box(-100, 0, 100, 130), 50);
  EXPECT_EQ(grid.cellOf(-100, 0), 0);
  EXPECT_EQ(grid.cellOf(-50.001, 49.999), 0);
  EXPECT_EQ(grid.cellOf(-50, 0), 1);  // a cell owns its lower edges
  EXPECT_EQ(grid.cellOf(99, 0), 3);
  EXPECT_EQ(grid.cellOf(-100, 50), 4);
  EXPECT_EQ(grid.cellOf(30, 120), 2 * 4 + 2);
  for (int cell = 0; cell < grid.cellCount(); ++cell) {
    double x = -100 + 50 * (grid.columnOfCell(cell) + 0.5);
    double z = 50 * (grid.rowOfCell(cell) + 0.5);
    EXPECT_EQ(grid.cellOf(x, z), cell);
  }
}

TEST(InterestGrid, PointsOutsideClampToTheEdgeCells) {
  InterestGrid grid(box(0, 0, 200, 200), 50);
  EXPECT_EQ(grid.cellOf(-10, -10), 0);
  EXPECT_EQ(grid.cellOf(200, 200), grid.cellCount() - 1);  // the far edge itself
  EXPECT_EQ(grid.cellOf(1e6, 25), 3);
  EXPECT_EQ(grid.cellOf(25, 1e6), 12);
  EXPECT_EQ(grid.cellOf(-1e6, 1e6), 12);
}

TEST(InterestGrid, ExtremeAndNonFiniteCoordinatesStayInTheGrid) {
  // A runaway entity must not index outside the grid (or overflow converting to int).
  InterestGrid grid(box(0, 0, 200, 200), 50);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(grid.cellOf(1e300, -1e300), 3);
  EXPECT_EQ(grid.cellOf(inf, inf), 15);
  EXPECT_EQ(grid.cellOf(-inf, -inf), 0);
  int nan_cell = grid.cellOf(std::nan(""), std::nan(""));
  EXPECT_GE(nan_cell, 0);
  EXPECT_LT(nan_cell, grid.cellCount());
  for (int cell : grid.cellsWithin(1e300, 1e300, 1e300)) {
    EXPECT_GE(cell, 0);
    EXPECT_LT(cell, grid.cellCount());
  }
}

// Every cell whose closed square meets the closed disc, by checking all cells.
std::vector<int> bruteForceWithin(const SceneBox& world, double size, int columns, int rows,
                                  double x, double z, double r) {
  std::vector<int> out;
  for (int iz = 0; iz < rows; ++iz) {
    for (int ix = 0; ix < columns; ++ix) {
      double x0 = world.min.x + ix * size, z0 = world.min.z + iz * size;
      double dx = std::max({x0 - x, 0.0, x - (x0 + size)});
      double dz = std::max({z0 - z, 0.0, z - (z0 + size)});
      if (dx * dx + dz * dz <= r * r) out.push_back(iz * columns + ix);
    }
  }
  return out;
}

TEST(InterestGrid, CellsWithinMatchesBruteForceAtRandomPoints) {
  SceneBox world = box(-120, -40, 280, 160);
  InterestGrid grid(world, 25);
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> x(-180, 340), z(-100, 220), r(0, 90);
  for (int i = 0; i < 2000; ++i) {
    double px = x(gen), pz = z(gen), pr = r(gen);
    ASSERT_EQ(grid.cellsWithin(px, pz, pr),
              bruteForceWithin(world, 25, grid.columns(), grid.rows(), px, pz, pr))
        << "at (" << px << ", " << pz << ") r " << pr;
  }
}

TEST(InterestGrid, CellsWithinMatchesBruteForceOnCellEdges) {
  // Points and radii on whole metres hit discs that just touch a cell edge or corner.
  SceneBox world = box(0, 0, 200, 150);
  InterestGrid grid(world, 50);
  for (int px = -50; px <= 250; px += 25) {
    for (int pz = -50; pz <= 200; pz += 25) {
      for (int pr : {0, 25, 50, 60, 75, 100}) {
        ASSERT_EQ(grid.cellsWithin(px, pz, pr),
                  bruteForceWithin(world, 50, grid.columns(), grid.rows(), px, pz, pr))
            << "at (" << px << ", " << pz << ") r " << pr;
      }
    }
  }
}

TEST(InterestGrid, CellsWithinIncludesTheCellOfAPointInside) {
  InterestGrid grid(box(0, 0, 200, 200), 50);
  EXPECT_EQ(grid.cellsWithin(60, 60, 0), std::vector<int>{5});
  EXPECT_EQ(grid.cellsWithin(75, 75, 10), std::vector<int>{5});
  EXPECT_EQ(grid.cellsWithin(100, 100, 1000).size(), 16u);
}

}  // namespace
}  // namespace zonesim
