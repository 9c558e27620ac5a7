// crowd_bench [--agents 1000,10000,100000] [--lanes 1,2,4,8] [--steps N]
//              [--only flock|flow|lod|lod-flock|lod-sweep|overlap] [--lod-seconds S]
//              [--crowded LIST] [--overlap-seconds S] [--overlap-every K]
//              [--separation-weight LIST] [--separation-radius R] [--max-force F]
//              [--body-radius LIST] [--place-apart] [--flock-body-radius LIST]
// Prints markdown tables: ms per step and agent updates per second for flocking and flow
// fields on one core, flow field build time, and (--only lod: flow crowds; --only lod-flock:
// flocks) AI time and outcome drift with and without level of detail; --crowded adds flow LOD
// variants that keep agents at full detail where a 4 m cell holds that many agents or more;
// --only lod-sweep prints CSV of time against outcome drift over a grid of LOD bands;
// --only overlap: the deepest overlap between two agents' bodies over a run of the flow crowd
// and of the flock, next to the step time (--separation-weight, --separation-radius and
// --max-force change the flow crowd's settings for it; --body-radius runs it with bodies kept
// apart, crowd/keep_apart.h, 0 for none, and --flock-body-radius the flock; --place-apart
// places both crowds without overlaps). The
// flock and flow tables end with a digest of the final state, so that two builds can be shown to
// step bitwise alike.

#include <cstdio>
#include <cstring>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

#include "ai/grid_map.h"
#include "bench/bench_args.h"
#include "common/rng.h"
#include "crowd/flock.h"
#include "crowd/flow_crowd.h"
#include "crowd/lod.h"
#include "crowd/overlap.h"

using namespace zonesim;
using namespace zonesim::crowd;

namespace {

// Thread CPU time, not wall time: the benchmark machine is shared, and time spent
// descheduled is not the algorithm's (caches shared with other work still show).
struct Clock {
  using time_point = double;
  static double now() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
  }
};
double msSince(double t0) {
  return Clock::now() - t0;
}

struct Agents {
  std::vector<std::uint64_t> ids;
  std::vector<Vec2> pos, vel;
  AgentSpan span() { return AgentSpan{ids, pos, vel}; }
};

// FNV-1a over the bytes of every id, position and velocity, in storage order: equal digests
// mean bitwise equal states (up to hash collisions).
std::uint64_t stateDigest(const Agents& a) {
  std::uint64_t h = 1469598103934665603ULL;
  const auto mix = [&h](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  };
  mix(a.ids.data(), a.ids.size() * sizeof(std::uint64_t));
  mix(a.pos.data(), a.pos.size() * sizeof(Vec2));
  mix(a.vel.data(), a.vel.size() * sizeof(Vec2));
  return h;
}

/// n flockers placed uniformly in a square of this side with random velocities up to 1 m/s
/// a component, from the seed; ids are unrelated to position.
/// Points placed at random on [0, width) x [0, height) that keep `apart` (> 0) from each
/// other: a candidate too close to one already placed is refused (1 m cells of the area).
class Spacing {
 public:
  Spacing(double width, double height, double apart)
      : width_(int(std::ceil(width))),
        height_(int(std::ceil(height))),
        apart_(apart),
        cells_(apart > 0 ? std::size_t(width_) * height_ : 0) {}
  /// True (and `p` is kept) when `p` keeps the spacing from every point kept so far.
  bool admit(Vec2 p) {
    if (apart_ <= 0) return true;
    const int reach = int(std::ceil(apart_));
    for (int y = int(p.y) - reach; y <= int(p.y) + reach; ++y)
      for (int x = int(p.x) - reach; x <= int(p.x) + reach; ++x) {
        if (x < 0 || y < 0 || x >= width_ || y >= height_) continue;
        for (Vec2 q : cells_[std::size_t(y) * width_ + x])
          if (lengthSq(q - p) < apart_ * apart_) return false;
      }
    cells_[std::size_t(int(p.y)) * width_ + int(p.x)].push_back(p);
    return true;
  }

 private:
  int width_, height_;
  double apart_;
  std::vector<std::vector<Vec2>> cells_;
};

// `apart` > 0: no two agents closer than it (candidates that would be are drawn again).
Agents flockInSquare(int n, double side, std::uint64_t seed, double apart = 0) {
  Agents a;
  Pcg32 rng(seed, seed);
  Spacing spacing(side, side, apart);
  while (int(a.ids.size()) < n) {
    const Vec2 p{rng.uniform(0, side), rng.uniform(0, side)};
    const Vec2 v{rng.uniform(-1, 1), rng.uniform(-1, 1)};
    if (!spacing.admit(p)) continue;
    a.ids.push_back(std::uint64_t(a.ids.size()) * 2654435761ULL);
    a.pos.push_back(p);
    a.vel.push_back(v);
  }
  return a;
}

void benchFlock(const std::vector<int>& counts, const std::vector<int>& laneList, int steps) {
  std::printf(
      "\nFlocking (density 0.5 agents/m^2, neighbour radius 3 m, %d steps of 1/30 s; "
      "storage: random = ids and array order unrelated to position, cell = arrays reordered "
      "into the grid's cell order once before timing)\n\n",
      steps);
  std::printf(
      "| agents | storage | lanes | ms/step | agent updates/s | neighbours/agent | digest |\n"
      "|---|---|---|---|---|---|---|\n");
  for (int n : counts) {
    for (bool sorted : {false, true})
      for (int lanes : laneList) {
        Agents a = flockInSquare(n, std::sqrt(n / 0.5), 1);
        Flock flock{FlockSettings{}};
        // Agents per pass over the neighbour cells: 1, 2 (SSE2) or 4 (AVX); same results.
        int used = flock.useLanes(lanes);
        for (int k = 0; k < 5; ++k) flock.step(a.span(), {}, 1.0 / 30);  // warm the buffers
        if (sorted) {
          // What an entity store kept in spatial order would hand over (agents move little per
          // tick, so the order stays nearly sorted between occasional re-sorts).
          Agents b;
          for (const GridEntry& e : flock.grid().entries()) {
            b.ids.push_back(a.ids[e.src]);
            b.pos.push_back(a.pos[e.src]);
            b.vel.push_back(a.vel[e.src]);
          }
          a = std::move(b);
        }
        auto t0 = Clock::now();
        for (int k = 0; k < steps; ++k) flock.step(a.span(), {}, 1.0 / 30);
        double ms = msSince(t0) / steps;
        // Mean neighbours within the radius, from the last grid (not timed).
        long long pairs = 0;
        for (const GridEntry& e : flock.grid().entries())
          flock.grid().forEachNear(e.pos, 3.0, [&](const GridEntry& o) {
            if (o.id != e.id && lengthSq(o.pos - e.pos) < 9.0) ++pairs;
          });
        std::printf("| %d | %s | %d | %.3f | %.3g | %.1f | %016llx |\n", n,
                    sorted ? "cell" : "random", used, ms, n / (ms * 1e-3), double(pairs) / n,
                    static_cast<unsigned long long>(stateDigest(a)));
      }
  }
}

ai::GridMap benchMap() {
  return ai::loadMovingAiMap(std::string(ZONESIM_SOURCE_DIR) +
                             "/tests/data/movingai/random512-10-0.map");
}

// Destinations: four cells near the corners of the map, all mutually reachable.
std::vector<ai::Cell> cornerGoals(const ai::GridMap& map) {
  std::vector<ai::Cell> goals;
  for (ai::Cell c : {ai::Cell{20, 20}, ai::Cell{490, 20}, ai::Cell{20, 490}, ai::Cell{490, 490}}) {
    while (!map.passable(c.x, c.y)) ++c.x;
    goals.push_back(c);
  }
  return goals;
}

// n agents on random cells from which their destination (i mod 4) is reachable.
// `apart` > 0: no two agents closer than it (candidates that would be are drawn again).
void placeFlowAgents(const FlowCrowd& crowd, const ai::GridMap& map, int n, Agents& a,
                     std::vector<std::uint16_t>& dest, double apart = 0) {
  Pcg32 rng(2, 2);
  Spacing spacing(map.width(), map.height(), apart);
  while (int(a.ids.size()) < n) {
    Vec2 p{rng.uniform(0, map.width()), rng.uniform(0, map.height())};
    int d = int(a.ids.size() % crowd.destinationCount());
    if (crowd.field(d).distance(crowd.frame().cellOf(p)) < 0) continue;
    if (!spacing.admit(p)) continue;
    a.ids.push_back(std::uint64_t(a.ids.size()) * 2654435761ULL);
    a.pos.push_back(p);
    a.vel.push_back(Vec2{});
    dest.push_back(std::uint16_t(d));
  }
}

void benchFlow(const std::vector<int>& counts, int steps) {
  ai::GridMap map = benchMap();
  FlowCrowd crowd(map, MapFrame{}, FlowCrowdSettings{});
  auto t0 = Clock::now();
  for (ai::Cell g : cornerGoals(map)) crowd.addDestination(g);
  double buildMs = msSince(t0) / crowd.destinationCount();
  std::printf(
      "\nFlow fields on random512-10-0 (512x512, 1 m cells), 4 destinations: build %.1f "
      "ms per field (Dijkstra + directions), %.2f MiB per field\n\n",
      buildMs, crowd.field(0).bytes() / 1048576.0);
  std::printf("| agents | ms/step | agent updates/s | digest |\n|---|---|---|---|\n");
  for (int n : counts) {
    Agents a;
    std::vector<std::uint16_t> dest;
    placeFlowAgents(crowd, map, n, a, dest);
    std::vector<std::uint8_t> arrived(a.ids.size(), 0);
    for (int k = 0; k < 5; ++k) crowd.step(a.span(), dest, arrived, {}, 1.0 / 30);
    auto t1 = Clock::now();
    for (int k = 0; k < steps; ++k) crowd.step(a.span(), dest, arrived, {}, 1.0 / 30);
    double ms = msSince(t1) / steps;
    std::printf("| %d | %.3f | %.3g | %016llx |\n", n, ms, n / (ms * 1e-3),
                static_cast<unsigned long long>(stateDigest(a)));
  }
}

struct LodRun {
  double msPerTick = 0;
  std::size_t updates = 0;
  std::vector<int> arrival;  // tick of arrival per agent, -1 when not arrived
  std::vector<Vec2> endPos;
};

/// How far a LOD run's outcome moved from the full-detail run of the same agents: arrivals
/// (counted, and compared where both arrived, in seconds: `seconds` per arrival unit) and end
/// positions (all agents).
struct OutcomeDrift {
  int arrived = 0, both = 0;
  double sumDt = 0, maxDt = 0, sumErr = 0, maxErr = 0;
};

template <class Run>
OutcomeDrift outcomeDrift(const Run& full, const Run& lod, double seconds) {
  OutcomeDrift d;
  for (std::size_t i = 0; i < full.arrival.size(); ++i) {
    d.arrived += lod.arrival[i] >= 0;
    if (full.arrival[i] >= 0 && lod.arrival[i] >= 0) {
      const double dt = std::abs(double(full.arrival[i] - lod.arrival[i])) * seconds;
      d.sumDt += dt;
      d.maxDt = std::max(d.maxDt, dt);
      ++d.both;
    }
    const double e = length(full.endPos[i] - lod.endPos[i]);
    d.sumErr += e;
    d.maxErr = std::max(d.maxErr, e);
  }
  return d;
}

LodRun runLod(const ai::GridMap& map, int n, int ticks, const LodSettings* lodSettings) {
  FlowCrowd crowd(map, MapFrame{}, FlowCrowdSettings{});
  for (ai::Cell g : cornerGoals(map)) crowd.addDestination(g);
  Agents a;
  std::vector<std::uint16_t> dest;
  placeFlowAgents(crowd, map, n, a, dest);
  std::vector<std::uint8_t> arrived(a.ids.size(), 0);
  std::vector<std::int64_t> last(a.ids.size(), -1);
  const std::vector<Vec2> players{{150, 150}, {360, 300}};
  LodRun r;
  r.arrival.assign(a.ids.size(), -1);
  std::optional<LevelOfDetail> lod;
  if (lodSettings) lod.emplace(*lodSettings);
  const bool crowding_on = lodSettings && lodSettings->crowded_count > 0;
  std::vector<std::uint32_t> crowding;
  std::vector<std::uint8_t> walking;
  const double dt = 1.0 / 20;
  double cpu = 0;
  for (int t = 0; t < ticks; ++t) {
    double t0 = Clock::now();
    StepPlan plan;
    if (lod) {
      if (crowding_on) {
        // Agents still walking count toward their cell's crowding; arrived ones have left.
        walking.resize(arrived.size());
        for (std::size_t i = 0; i < arrived.size(); ++i) walking[i] = !arrived[i];
        crowdingCounts(a.pos, walking, {}, lodSettings->crowded_cell, crowding);
      }
      plan = lod->plan(a.ids, a.pos, players, t, dt, last, crowding);
      r.updates += lod->updated();
    } else {
      r.updates += a.ids.size();
    }
    crowd.step(a.span(), dest, arrived, {}, dt, plan);
    cpu += msSince(t0);
    for (std::size_t i = 0; i < a.ids.size(); ++i)
      if (arrived[i] && r.arrival[i] < 0) r.arrival[i] = t;
  }
  r.msPerTick = cpu / ticks;
  r.endPos = a.pos;
  return r;
}

void benchLod(const std::vector<int>& counts, double seconds, const std::vector<int>& crowded) {
  ai::GridMap map = benchMap();
  const int ticks = int(seconds * 20);
  LodSettings cheap;  // defaults: far agents ride the field without the neighbour query
  LodSettings steered = cheap;
  steered.far_steers = true;
  // far-field, plus full detail wherever a 4 m cell holds `crowded` agents or more.
  std::vector<LodSettings> variants{cheap, steered};
  for (int c : crowded) {
    variants.push_back(cheap);
    variants.back().crowded_count = c;
  }
  const auto name = [](const LodSettings& s) {
    if (s.crowded_count > 0) return "crowded-" + std::to_string(s.crowded_count);
    return std::string(s.far_steers ? "far-steer" : "far-field");
  };
  std::printf(
      "\nLOD: flow crowd on random512-10-0, 4 destinations, 2 players at (150,150) and "
      "(360,300), %d ticks of 1/20 s; near %.0f m every tick, mid to %.0f m every %d "
      "ticks, far every %d ticks; variant far-field: far agents without steering, "
      "far-steer: with. Errors against the full-detail run of the same agents.\n\n",
      ticks, cheap.near_radius, cheap.far_radius, cheap.mid_every, cheap.far_every);
  std::printf(
      "| agents | variant | ms/tick | speed-up | updates ratio | arrived | arrival "
      "|dt| mean s | max s | end pos error mean m | max m |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int n : counts) {
    LodRun full = runLod(map, n, ticks, nullptr);
    int arrivedFull = 0;
    for (int t : full.arrival) arrivedFull += t >= 0;
    std::printf("| %d | full | %.3f | 1.00 | 1.00 | %d | | | | |\n", n, full.msPerTick,
                arrivedFull);
    for (const LodSettings& s : variants) {
      LodRun lod = runLod(map, n, ticks, &s);
      const OutcomeDrift d = outcomeDrift(full, lod, 1.0 / 20.0);  // arrival in 1/20 s ticks
      std::printf("| %d | %s | %.3f | %.2f | %.2f | %d | %.3f | %.2f | %.3f | %.2f |\n", n,
                  name(s).c_str(), lod.msPerTick, full.msPerTick / lod.msPerTick,
                  double(full.updates) / double(lod.updates), d.arrived,
                  d.both ? d.sumDt / d.both : 0.0, d.maxDt, d.sumErr / n, d.maxErr);
    }
  }
}

struct FlockLodRun {
  double msPerTick = 0;
  std::size_t updates = 0;
  std::vector<double> arrival;  // s until the agent has made `progress` m toward the goal
  std::vector<Vec2> endPos;
  double closest = 0;  // smallest distance between two agents at the end, m
};

// A flock of n at 0.5/m^2 in a square, heading for a point far beyond its north-east corner
// (goal velocity 2 m/s, weight 1/s); players as in the flow case, scaled to the square.
FlockLodRun runFlockLod(int n, int ticks, double progress, const LodSettings* lodSettings) {
  const double side = std::sqrt(n / 0.5), dt = 1.0 / 30;
  Agents a = flockInSquare(n, side, 3);
  const Vec2 goal{side + 1000, side + 1000};
  const Vec2 dir = withLength(goal, 1.0);
  std::vector<double> start(a.ids.size());
  for (std::size_t i = 0; i < start.size(); ++i) start[i] = dot(a.pos[i], dir);
  const std::vector<Vec2> players{{0.3 * side, 0.3 * side}, {0.7 * side, 0.6 * side}};
  Flock flock{FlockSettings{}};
  std::optional<LevelOfDetail> lod;
  if (lodSettings) lod.emplace(*lodSettings);
  std::vector<Vec2> goal_vel(a.ids.size());
  FlockLodRun r;
  r.arrival.assign(a.ids.size(), -1);
  double cpu = 0;
  for (int t = 0; t < ticks; ++t) {
    double t0 = Clock::now();
    for (std::size_t i = 0; i < goal_vel.size(); ++i)
      goal_vel[i] = withLength(goal - a.pos[i], 2.0);
    StepPlan plan;
    if (lod) {
      plan = lod->plan(a.ids, a.pos, players, t, dt);
      r.updates += lod->updated();
    } else {
      r.updates += a.ids.size();
    }
    flock.step(a.span(), {}, dt, goal_vel, plan);
    cpu += msSince(t0);
    for (std::size_t i = 0; i < a.ids.size(); ++i)
      if (r.arrival[i] < 0 && dot(a.pos[i], dir) - start[i] >= progress)
        r.arrival[i] = (t + 1) * dt;
  }
  r.msPerTick = cpu / ticks;
  r.endPos = a.pos;
  // Closest pair at the end, through the flock's own grid (3 m cells).
  r.closest = 1e9;
  flock.step(a.span(), {}, 0.0);  // a zero step rebuilds the grid at the end positions
  for (const GridEntry& e : flock.grid().entries())
    flock.grid().forEachNear(e.pos, 1.0, [&](const GridEntry& o) {
      if (o.id != e.id) r.closest = std::min(r.closest, length(o.pos - e.pos));
    });
  return r;
}

void benchLodFlock(const std::vector<int>& counts, double seconds) {
  const int ticks = int(seconds * 30);
  const double progress = 40;
  LodSettings cheap;
  LodSettings steered = cheap;
  steered.far_steers = true;
  std::printf(
      "\nLOD: flock at 0.5/m^2 heading north-east (goal velocity 2 m/s), 2 players at (0.3, "
      "0.3) and (0.7, 0.6) of the square's side, %d ticks of 1/30 s; near %.0f m every tick, "
      "mid to %.0f m every %d ticks, far every %d ticks; far-goal: far agents follow the goal "
      "velocity only, far-steer: with the flock's terms. Arrival: time to make %.0f m toward "
      "the goal; errors against the full-detail run of the same agents.\n\n",
      ticks, cheap.near_radius, cheap.far_radius, cheap.mid_every, cheap.far_every, progress);
  std::printf(
      "| agents | variant | ms/tick | speed-up | updates ratio | arrived | arrival |dt| mean s "
      "| max s | end pos error mean m | max m | closest pair m |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int n : counts) {
    FlockLodRun full = runFlockLod(n, ticks, progress, nullptr);
    int arrivedFull = 0;
    for (double t : full.arrival) arrivedFull += t >= 0;
    std::printf("| %d | full | %.3f | 1.00 | 1.00 | %d | | | | | %.2f |\n", n, full.msPerTick,
                arrivedFull, full.closest);
    for (const LodSettings* s : {&cheap, &steered}) {
      FlockLodRun lod = runFlockLod(n, ticks, progress, s);
      const OutcomeDrift d = outcomeDrift(full, lod, 1.0);  // arrival already in s
      std::printf("| %d | %s | %.3f | %.2f | %.2f | %d | %.3f | %.2f | %.3f | %.2f | %.2f |\n", n,
                  s->far_steers ? "far-steer" : "far-goal", lod.msPerTick,
                  full.msPerTick / lod.msPerTick, double(full.updates) / double(lod.updates),
                  d.arrived, d.both ? d.sumDt / d.both : 0.0, d.maxDt, d.sumErr / n, d.maxErr,
                  lod.closest);
    }
  }
}

/// The LOD bands' work-precision sweep (issue 19): for flow crowds and flocks, each pair of a
/// near radius (the far radius 3x it, the middle band every 2 ticks) and a far period, the
/// time saved against the outcome's drift from full detail (mean arrival time difference).
/// CSV rows for bench/plot_lod_sweep.py.
/// One kind's rows of the sweep: `run(settings or null)` gives a run with msPerTick, updates
/// and arrival; `unit` converts its arrivals to seconds.
template <class Run>
void sweepRows(const char* kind, int n, std::initializer_list<double> nears, double unit,
               const Run& run) {
  const auto full = run(nullptr);
  for (double near : nears) {
    for (int k : {2, 4, 8, 16}) {
      LodSettings s;
      s.near_radius = near;
      s.far_radius = 3 * near;
      s.far_every = k;
      const auto lod = run(&s);
      const OutcomeDrift d = outcomeDrift(full, lod, unit);
      std::printf("%s,%d,%g,%g,%d,%.4f,%.3f,%.3f,arrival_drift_s,%.4f\n", kind, n, near, 3 * near,
                  k, lod.msPerTick, full.msPerTick / lod.msPerTick,
                  double(full.updates) / double(lod.updates), d.both ? d.sumDt / d.both : 0.0);
    }
  }
}

void benchLodSweep(const std::vector<int>& counts, double seconds) {
  ai::GridMap map = benchMap();
  std::printf(
      "kind,agents,near_radius,far_radius,far_every,ms_per_tick,speedup,updates_ratio,"
      "error_name,error\n");
  for (int n : counts) {
    const int flow_ticks = int(seconds * 20);
    sweepRows("flow", n, {20.0, 40.0, 80.0}, 1.0 / 20.0,
              [&](const LodSettings* s) { return runLod(map, n, flow_ticks, s); });
    const int flock_ticks = int(seconds * 30 / 4);  // the flock's 40 m take about 20 s
    sweepRows("flock", n, {10.0, 20.0, 40.0}, 1.0,
              [&](const LodSettings* s) { return runFlockLod(n, flock_ticks, 40, s); });
  }
}

/// Overlap over one run: the deepest overlap measured once the placement has settled, where
/// and when, and the cost of the measurement beside the step's.
struct OverlapRun {
  double placed = 0;     // deepest overlap of the random placement (step 0), m
  double deepest = 0;    // deepest overlap from `settle` s on, m
  double deepestAt = 0;  // when, s
  Vec2 deepestWhere;     // midpoint of that pair
  double last = 0;       // deepest overlap at the last measurement, m
  std::size_t lastPairs = 0;
  double stepMs = 0, measureMs = 0;
};

// Steps `steps` times; after every `every`-th step measures the overlap on the grid that step
// built (the positions at the start of the step: no extra build).
template <class Step, class Grid>
OverlapRun runOverlap(int steps, int every, double dt, double settle, double radius,
                      const Step& step, const Grid& grid) {
  OverlapRun r;
  double stepCpu = 0, measureCpu = 0;
  int measures = 0;
  for (int k = 0; k < steps; ++k) {
    double t0 = Clock::now();
    step();
    stepCpu += msSince(t0);
    if (k % every != 0 && k != steps - 1) continue;
    t0 = Clock::now();
    const Overlap o = deepestOverlap(grid(), radius);
    measureCpu += msSince(t0);
    ++measures;
    const double t = k * dt;  // the grid holds the state after k steps
    if (k == 0) r.placed = o.depth;
    if (t >= settle && o.depth > r.deepest) {
      r.deepest = o.depth;
      r.deepestAt = t;
      r.deepestWhere = o.at;
    }
    r.last = o.depth;
    r.lastPairs = o.pairs;
  }
  r.stepMs = stepCpu / steps;
  r.measureMs = measureCpu / measures;
  return r;
}

/// Flow crowd settings for the overlap runs (0: keep the default).
struct OverlapFlowSettings {
  std::vector<double> weights{0};
  std::vector<double> bodies{0};  // body_radius: agents kept apart (0: overlap allowed)
  std::vector<double> flockBodies{0};  // the same for the flock
  double separationRadius = 0, maxForce = 0;
  bool placeApart = false;  // place both crowds without overlaps (of their default bodies)
};

void benchOverlap(const std::vector<int>& counts, double seconds, int every,
                  const OverlapFlowSettings& flow) {
  const double dt = 1.0 / 30, settle = 5.0;
  const int steps = int(seconds / dt);
  // Bodies of the default settings: discs whose edges touch where separation starts.
  const double flowBody = FlowCrowdSettings{}.separation_radius / 2;
  const double flockBody = FlockSettings{}.separation_radius / 2;
  ai::GridMap map = benchMap();
  std::printf(
      "\nOverlap: agents are discs (flow %.2f m, flock %.2f m: half the default separation "
      "radius); overlap = 2 radius - centre distance of the closest pair, measured every %d "
      "step(s) on the step's own neighbour grid, %d steps of 1/30 s (%.0f s). Flow: "
      "random512-10-0, 4 destinations, arrived agents leave; flock: 0.5/m^2, no goal. "
      "`deepest`: from %.0f s on (the random placement overlaps by up to 2 radius); `placed`: "
      "at step 0.\n\n",
      flowBody, flockBody, every, steps, seconds, settle);
  std::printf(
      "| crowd | agents | separation radius | weight | max force | kept apart (body m) | placed m "
      "| deepest m | at s | where | last m | pairs overlapping at the end | arrived | ms/step "
      "| ms/measurement |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const auto row = [](const char* kind, int n, double sep, double w, double force, double body,
                      const OverlapRun& r, long arrived) {
    char kept[32] = "no";
    if (body > 0) std::snprintf(kept, sizeof kept, "%g", body);
    std::printf(
        "| %s | %d | %g | %g | %g | %s | %.4f | %.6f | %.1f | (%.1f, %.1f) | %.6f | %zu | %ld "
        "| %.3f | %.3f |\n",
        kind, n, sep, w, force, kept, r.placed, r.deepest, r.deepestAt, r.deepestWhere.x,
        r.deepestWhere.y, r.last, r.lastPairs, arrived, r.stepMs, r.measureMs);
  };
  for (int n : counts)
    for (double body : flow.bodies)
      for (double w : flow.weights) {
        FlowCrowdSettings fs;
        fs.body_radius = body;
        if (w > 0) fs.separation_weight = w;
        if (flow.separationRadius > 0) fs.separation_radius = flow.separationRadius;
        if (flow.maxForce > 0) fs.max_force = flow.maxForce;
        FlowCrowd crowd(map, MapFrame{}, fs);
        for (ai::Cell g : cornerGoals(map)) crowd.addDestination(g);
        Agents a;
        std::vector<std::uint16_t> dest;
        placeFlowAgents(crowd, map, n, a, dest, flow.placeApart ? 2 * flowBody : 0);
        std::vector<std::uint8_t> arrived(a.ids.size(), 0);
        const OverlapRun r = runOverlap(
            steps, every, dt, settle, flowBody,
            [&] { crowd.step(a.span(), dest, arrived, {}, dt); },
            [&]() -> const NeighbourGrid& { return crowd.grid(); });
        long done = 0;
        for (std::uint8_t f : arrived) done += f;
        row("flow", n, fs.separation_radius, fs.separation_weight, fs.max_force, body, r, done);
      }
  for (int n : counts)
    for (double body : flow.flockBodies) {
      FlockSettings fs;
      fs.body_radius = body;
      const double side = std::sqrt(n / 0.5);
      Agents a = flockInSquare(n, side, 1, flow.placeApart ? 2 * flockBody : 0);
      Flock flock{fs};
      const OverlapRun r = runOverlap(
          steps, every, dt, settle, flockBody, [&] { flock.step(a.span(), {}, dt); },
          [&]() -> const NeighbourGrid& { return flock.grid(); });
      row("flock", n, fs.separation_radius, fs.separation_weight, fs.max_force, body, r, 0);
    }
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // rows appear as they are measured
  std::vector<int> counts{1000, 10000, 100000};
  std::vector<int> lanes{1, 2, 4, 8};
  int steps = 30;
  double lodSeconds = 200;
  std::string only;
  std::vector<int> crowded;
  double overlapSeconds = 60;
  int overlapEvery = 1;
  OverlapFlowSettings overlapFlow;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--agents") && i + 1 < argc)
      counts = bench::parseCounts("--agents", argv[++i]);
    else if (!std::strcmp(argv[i], "--lanes") && i + 1 < argc)
      lanes = bench::parseCounts("--lanes", argv[++i]);
    else if (!std::strcmp(argv[i], "--steps") && i + 1 < argc)
      steps = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc)
      only = argv[++i];
    else if (!std::strcmp(argv[i], "--lod-seconds") && i + 1 < argc)
      lodSeconds = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--crowded") && i + 1 < argc)
      crowded = bench::parseCounts("--crowded", argv[++i]);
    else if (!std::strcmp(argv[i], "--overlap-seconds") && i + 1 < argc)
      overlapSeconds = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--overlap-every") && i + 1 < argc)
      overlapEvery = std::max(1, std::stoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--separation-weight") && i + 1 < argc) {
      overlapFlow.weights.clear();
      for (int w : bench::parseCounts("--separation-weight", argv[++i]))
        overlapFlow.weights.push_back(w);
    } else if (!std::strcmp(argv[i], "--separation-radius") && i + 1 < argc)
      overlapFlow.separationRadius = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--max-force") && i + 1 < argc)
      overlapFlow.maxForce = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--place-apart"))
      overlapFlow.placeApart = true;
    else if (!std::strcmp(argv[i], "--body-radius") && i + 1 < argc)
      overlapFlow.bodies = bench::parseReals("--body-radius", argv[++i]);
    else if (!std::strcmp(argv[i], "--flock-body-radius") && i + 1 < argc)
      overlapFlow.flockBodies = bench::parseReals("--flock-body-radius", argv[++i]);
    else {
      std::fprintf(stderr,
                   "usage: crowd_bench [--agents LIST] [--lanes LIST] [--steps N]\n"
                   "                   [--only flock|flow|lod|lod-flock|lod-sweep|overlap] "
                   "[--lod-seconds S]\n"
                   "                   [--crowded LIST] [--overlap-seconds S] "
                   "[--overlap-every K]\n"
                   "                   [--separation-weight LIST] [--separation-radius R] "
                   "[--max-force F] [--body-radius LIST] [--place-apart]\n"
                   "                   [--flock-body-radius LIST]\n");
      return 2;
    }
  }
  if (only.empty() || only == "flock") benchFlock(counts, lanes, steps);
  if (only.empty() || only == "flow") benchFlow(counts, steps);
  if (only == "lod") benchLod(counts, lodSeconds, crowded);
  if (only == "lod-flock") benchLodFlock(counts, lodSeconds);
  if (only == "lod-sweep") benchLodSweep(counts, lodSeconds);
  if (only == "overlap") benchOverlap(counts, overlapSeconds, overlapEvery, overlapFlow);
  return 0;
}
