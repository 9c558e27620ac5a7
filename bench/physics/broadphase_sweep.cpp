// broadphase_sweep: the four broadphases (brute force, sweep and prune, uniform grid, AABB
// tree) on the same boxes, by body count, density and layout. They return the same pairs
// (checked here on every case), so the choice is about cost alone: this prints the time of one
// findPairs per kind (median of REPEATS, every body moving) and which is cheapest, as CSV rows
// for plot_broadphase_sweep.py.
//
//   build/bin/broadphase_sweep [--repeats 5] [--sizes 1000,10000]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "bench/bench_args.h"
#include "physics/broadphase.h"

using namespace zonesim;
using namespace zonesim::physics;

namespace {

constexpr const char* kKindNames[] = {"brute_force", "sweep_and_prune", "uniform_grid",
                                      "aabb_tree"};

/// Unit boxes (half extent 0.5) at `density` bodies per m^3: spread through a cube ("volume"),
/// on a 1 m thick floor ("floor", a crowd on the ground), or half of them packed 10x denser in
/// a corner ("clustered").
std::vector<Aabb> layout(const std::string& kind, int n, double density, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<Aabb> boxes;
  boxes.reserve(std::size_t(n));
  const auto place = [&](double sx, double sy, double sz, double ox) {
    std::uniform_real_distribution<double> x(ox, ox + sx), y(0, sy), z(0, sz);
    const Vec3 c(x(rng), y(rng), z(rng));
    boxes.push_back(Aabb{c - Vec3::Constant(0.5), c + Vec3::Constant(0.5)});
  };
  if (kind == "floor") {
    const double side = std::sqrt(double(n) / density);  // bodies per m^2 of a 1 m layer
    for (int i = 0; i < n; ++i) place(side, 1.0, side, 0.0);
  } else if (kind == "clustered") {
    const double side = std::cbrt(double(n) / density);
    const double dense = std::cbrt(double(n / 2) / (10.0 * density));
    for (int i = 0; i < n; ++i) {
      if (i % 2 == 0)
        place(dense, dense, dense, 0.0);
      else
        place(side, side, side, 0.0);
    }
  } else {
    const double side = std::cbrt(double(n) / density);
    for (int i = 0; i < n; ++i) place(side, side, side, 0.0);
  }
  return boxes;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 5;
  std::vector<int> sizes{1000, 10000};
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--sizes")) sizes = bench::parseCounts("--sizes", argv[i + 1]);
  }
  std::printf(
      "layout,bodies,density,pairs,brute_force_ms,sweep_and_prune_ms,uniform_grid_ms,"
      "aabb_tree_ms,cheapest\n");
  for (const char* shape : {"volume", "floor", "clustered"}) {
    for (int n : sizes) {
      for (double density : {0.01, 0.05, 0.2, 0.5}) {
        const std::vector<Aabb> boxes = layout(shape, n, density, 7);
        const std::vector<std::uint8_t> moving(boxes.size(), 1);
        std::vector<ProxyPair> reference;
        double ms[4] = {};
        for (int k = 0; k < 4; ++k) {
          // Brute force at 10k+ bodies is 50M box tests a call: time it once.
          const int runs = (k == 0 && n > 5000) ? 1 : repeats;
          Broadphase bp{BroadphaseKind(k)};
          std::vector<ProxyPair> pairs;
          std::vector<double> times;
          for (int r = 0; r < runs; ++r) {
            const auto t0 = std::chrono::steady_clock::now();
            bp.findPairs(boxes, moving, pairs);
            times.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count());
          }
          std::sort(times.begin(), times.end());
          ms[k] = times[times.size() / 2];
          if (k == 0) {
            reference = pairs;
          } else if (pairs != reference) {
            std::fprintf(stderr, "%s %d %.2f: %s found %zu pairs, brute force %zu\n", shape, n,
                         density, kKindNames[k], pairs.size(), reference.size());
            return 1;
          }
        }
        const int best = int(std::min_element(ms, ms + 4) - ms);
        std::printf("%s,%d,%.2f,%zu,%.3f,%.3f,%.3f,%.3f,%s\n", shape, n, density, reference.size(),
                    ms[0], ms[1], ms[2], ms[3], kKindNames[best]);
        std::fflush(stdout);
      }
    }
  }
}
