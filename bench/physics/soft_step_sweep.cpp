// soft_step_sweep: how stiff the soft step's contact springs may be at the default
// step (one step of 1/60 s, 10 velocity and 2 position iterations). For each body-body spring
// frequency (as a fraction of the sub-step rate) and each spring for contacts with the static
// floor, it prints the largest drift (hypot of sideways and vertical) of any box in a 20-box
// column after 60 s, and of a 100:1 pair and a light-light-heavy column after 30 s.
// Stiffer springs sag less; the question is where the column or the mass ratio gives way.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "physics/box_column.h"
#include "physics/world.h"

namespace {

using zonesim::Vec3;
using namespace zonesim::physics;

/// Largest displacement of any box of the shared unit-cube column (densities bottom to top).
double columnDrift(const WorldSettings& settings, const std::vector<double>& densities,
                   double seconds) {
  BoxColumn column(settings, densities);
  column.run(seconds);
  return column.drift().total;
}

}  // namespace

int main() {
  std::printf(
      "body_fraction,static_fraction,hertz_body,column20_60s_m,pair100to1_30s_m,"
      "light_light_heavy_30s_m\n");
  const double rate = 300.0;  // Sub-step rate: 60 Hz times 10 iterations / 2.
  for (double body : {0.25, 0.30, 0.33, 0.34, 0.35, 0.36, 0.37, 0.38}) {
    for (double floor : {0.25, body}) {
      WorldSettings settings;
      settings.solver.kind = SolverKind::SoftStep;
      settings.solver.velocity_iterations = 10;
      settings.solver.position_iterations = 2;
      settings.solver.contact_rate_fraction = body;
      settings.solver.static_contact_rate_fraction = floor;
      const double column = columnDrift(settings, std::vector<double>(20, 1000.0), 60.0);
      const double pair = columnDrift(settings, {1000.0, 100000.0}, 30.0);
      const double llh = columnDrift(settings, {1000.0, 1000.0, 100000.0}, 30.0);
      std::printf("%.2f,%.2f,%.0f,%.3e,%.3e,%.3e\n", body, floor, body * rate, column, pair, llh);
      std::fflush(stdout);
      if (body == 0.25) break;  // Both springs are the same at the default.
    }
  }
  return 0;
}
