// The flock's neighbour search: the device's pair sort against std::stable_sort, and the grid
// (CPU counting sort, device cell/sort/range kernels) against brute force: the same neighbour
// set for every boid, including boids outside the bounds that count in the border cells.

#include "gpu/boid_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "gpu/cl_boids.h"
#include "gpu/cl_error.h"
#include "gpu/cl_sort.h"
#include "gpu/cpu_boids.h"
#include "tests/gpu/device_fixture.h"

namespace zonesim::gpu {
namespace {

const FlockBounds kBounds{{-10, 0, -10}, {10, 8, 10}};
const BoidParams kParams{};  // perception radius 2: a 10 x 4 x 10 grid

// Boids spread over the bounds plus 5% up to 6 m outside, on float values so that the device
// sees the same positions as the host.
std::vector<Vec3d> scatter(std::size_t n, std::uint64_t seed) {
  Pcg32 rng(seed, 9);
  std::vector<Vec3d> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    double pad = i % 20 == 0 ? 6.0 : 0.0;
    auto draw = [&](double lo, double hi) {
      return double(float(lo - pad + (hi - lo + 2 * pad) * rng.uniform()));
    };
    out[i] = {draw(kBounds.min.x, kBounds.max.x), draw(kBounds.min.y, kBounds.max.y),
              draw(kBounds.min.z, kBounds.max.z)};
  }
  return out;
}

std::vector<std::uint32_t> bruteForce(std::span<const Vec3d> x, std::uint32_t i, double r) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t j = 0; j < x.size(); ++j) {
    double dx = x[j].x - x[i].x, dy = x[j].y - x[i].y, dz = x[j].z - x[i].z;
    if (j != i && dx * dx + dy * dy + dz * dz < r * r) out.push_back(j);
  }
  return out;
}

// Every boid's grid neighbours, as a set, equal brute force; returns the total neighbour count.
std::size_t expectSameNeighbours(const CellIndex& index, std::span<const Vec3d> x) {
  GridSpec grid = makeGrid(kBounds, kParams);
  std::vector<std::uint32_t> sorted(index.order.begin(), index.order.end());
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::uint32_t> ids(x.size());
  std::iota(ids.begin(), ids.end(), 0u);
  EXPECT_EQ(sorted, ids) << "order must be a permutation of the boids";
  std::size_t total = 0;
  std::vector<std::uint32_t> found;
  for (std::uint32_t i = 0; i < x.size(); ++i) {
    gridNeighbours(grid, index, x, i, kParams.perception_radius, found);
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, bruteForce(x, i, kParams.perception_radius)) << "boid " << i;
    total += found.size();
  }
  return total;
}

TEST(BoidGrid, CpuIndexFindsTheBruteForceNeighbours) {
  std::vector<Vec3d> x = scatter(3000, 1);
  CellIndex index;
  buildCellIndex(makeGrid(kBounds, kParams), x, index);
  EXPECT_GT(expectSameNeighbours(index, x), 20'000u) << "the flock must be dense enough";
}

TEST(BoidGrid, DeviceIndexFindsTheBruteForceNeighbours) {
  ZS_REQUIRE_OPENCL();
  // 3000 boids pad to 4096, so the sort runs both its global and its local stages.
  std::vector<Vec3d> x = scatter(3000, 2);
  std::vector<Vec3d> v(x.size());
  ClBoids boids(test::sharedRuntime(), makeGrid(kBounds, kParams), kBounds, kParams);
  boids.setAgents(x, v);
  CellIndex index;
  boids.buildIndex(index);
  EXPECT_GT(expectSameNeighbours(index, x), 20'000u);
  // Within a cell, ids ascend: the device's order is the CPU's stable counting sort.
  CellIndex reference;
  buildCellIndex(makeGrid(kBounds, kParams), x, reference);
  EXPECT_EQ(index.order, reference.order);
}

TEST(BoidGrid, RejectsBadBoundsAndParams) {
  EXPECT_THROW(makeGrid({{0, 0, 0}, {0, 1, 1}}, kParams), std::invalid_argument);
  BoidParams bad = kParams;
  bad.perception_radius = 0;
  EXPECT_THROW(makeGrid(kBounds, bad), std::invalid_argument);
  bad = kParams;
  bad.min_speed = 6;
  bad.max_speed = 5;
  EXPECT_THROW(makeGrid(kBounds, bad), std::invalid_argument);
  bad = kParams;
  bad.perception_radius = 0.01;  // 2000^2 x 800 cells
  EXPECT_THROW(makeGrid(kBounds, bad), std::invalid_argument);
}

class PairSort : public ::testing::TestWithParam<std::size_t> {};

// Keys with many duplicates, values distinct: the result is std::stable_sort by key.
TEST_P(PairSort, MatchesStableSortByKey) {
  ZS_REQUIRE_OPENCL();
  const std::size_t n = GetParam();
  const std::size_t padded = ClPairSort::paddedLength(n);
  Pcg32 rng(n, 1);
  std::vector<cl_uint> keys(padded, 0xffffffffu), vals(padded);
  std::vector<std::pair<cl_uint, cl_uint>> expected;
  for (std::size_t i = 0; i < padded; ++i) {
    vals[i] = cl_uint(i);
    if (i < n) {
      keys[i] = cl_uint(rng.uniform() * 50);
      expected.push_back({keys[i], vals[i]});
    }
  }
  std::stable_sort(expected.begin(), expected.end(),
                   [](auto& a, auto& b) { return a.first < b.first; });
  const ClRuntime& rt = *test::sharedRuntime();
  ClBuffer k = rt.createBuffer(padded * sizeof(cl_uint));
  ClBuffer v = rt.createBuffer(padded * sizeof(cl_uint));
  checkCl(clEnqueueWriteBuffer(rt.queue(), k.get(), CL_TRUE, 0, padded * 4, keys.data(), 0, nullptr,
                               nullptr),
          "write");
  checkCl(clEnqueueWriteBuffer(rt.queue(), v.get(), CL_TRUE, 0, padded * 4, vals.data(), 0, nullptr,
                               nullptr),
          "write");
  ClPairSort sort(test::sharedRuntime());
  sort.enqueue(k.get(), v.get(), padded);
  checkCl(clEnqueueReadBuffer(rt.queue(), k.get(), CL_TRUE, 0, padded * 4, keys.data(), 0, nullptr,
                              nullptr),
          "read");
  checkCl(clEnqueueReadBuffer(rt.queue(), v.get(), CL_TRUE, 0, padded * 4, vals.data(), 0, nullptr,
                              nullptr),
          "read");
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(keys[i], expected[i].first) << "at " << i;
    ASSERT_EQ(vals[i], expected[i].second) << "at " << i;
  }
  for (std::size_t i = n; i < padded; ++i) ASSERT_EQ(keys[i], 0xffffffffu) << "padding at " << i;
}

// 1 and 2 pad to one pair; 300 fits one work-group; 5000 and 70000 need global stages.
INSTANTIATE_TEST_SUITE_P(Lengths, PairSort, ::testing::Values(1, 2, 300, 5000, 70000));

}  // namespace
}  // namespace zonesim::gpu
