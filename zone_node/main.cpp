// zone_node: one MPI rank per zone. Runs as a singleton without mpirun (one zone).
//   mpirun -np 4 zone_node --scene scenes/demo.yaml --duration 20 --realtime --metrics runs/x

#include <mpi.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>

#include "common/cli.h"
#include "common/metrics.h"
#include "common/scene.h"
#include "common/stop_signal.h"
#include "zone_node/arrival_log.h"
#include "zone_node/cluster/checkpoint.h"
#include "zone_node/item_log.h"
#include "zone_node/state_dump.h"
#include "zone_node/truth_log.h"
#include "zone_node/zone_node.h"
#include "zone_node/zone_recorder.h"
#include "zone_node/zone_report.h"

namespace {

struct Options {
  std::string scene;
  std::uint64_t ticks = 0;
  double duration = 0;
  bool realtime = false;
  std::string metrics_dir;
  std::string dump_state;
  std::uint64_t dump_state_at = 0;  ///< 0: at the end of the run
  std::string arrivals;             ///< empty: no arrival file
  std::string restart;
  std::uint32_t truth_every = 0;
  std::string time_dilation = "scene";  ///< on, off, or as the scene says
  std::int64_t epoch = -1;              ///< -1: 0 for a fresh start, 1 after --restart
  double orphan_grace_s = 30;
  std::string ledger;  ///< sqlite:PATH or postgres:CONNINFO; empty: no ledger
  std::string record_dir;          ///< empty: no recording
  std::uint32_t record_every = 1;  ///< record one entity id in this many
  zonesim::zone::ZoneOptions zone = withSceneGpu();  ///< its gpu "scene": the scene's gpu.mode
  zonesim::CommonOptions common;

  static zonesim::zone::ZoneOptions withSceneGpu() {
    zonesim::zone::ZoneOptions z;
    z.gpu = "scene";
    return z;
  }
};

/// Sleeps until an absolute CLOCK_MONOTONIC time (fixed-rate ticks without drift).
void sleepUntil(const timespec& t) {
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR &&
         !zonesim::stopRequested()) {
  }
}

timespec addSeconds(timespec t, double s) {
  auto ns = std::int64_t(s * 1e9) + t.tv_nsec;
  t.tv_sec += ns / 1000000000;
  t.tv_nsec = ns % 1000000000;
  return t;
}

/// Whether CLOCK_MONOTONIC has passed t (a paced tick that ends after its deadline is late).
bool isPast(const timespec& t) {
  timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return now.tv_sec > t.tv_sec || (now.tv_sec == t.tv_sec && now.tv_nsec > t.tv_nsec);
}

/// All ranks stop together: any rank that saw a signal stops everyone.
bool anyRankStopping(MPI_Comm comm) {
  int mine = zonesim::stopRequested() ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm);
  return any != 0;
}

int run(const Options& o, MPI_Comm comm) {
  using namespace zonesim;
  Scene scene = loadScene(o.scene);
  if (o.time_dilation != "scene") scene.time_dilation.enabled = o.time_dilation == "on";
  zone::ZoneOptions zone_options = o.zone;
  if (zone_options.gpu == "scene") zone_options.gpu = scene.gpu_mode;
  zone_options.epoch = std::uint32_t(o.epoch >= 0 ? o.epoch : o.restart.empty() ? 0 : 1);
  zone_options.orphan_grace_ticks = int(std::lround(o.orphan_grace_s * scene.tick_rate));
  std::unique_ptr<zone::CheckpointImage> image;
  if (!o.restart.empty())
    image = std::make_unique<zone::CheckpointImage>(zone::readCheckpoint(o.restart));
  zone::ZoneNode node(scene, comm, zone_options, image.get());
  if (image)
    ZS_INFO("restarted from %s at tick %llu, epoch %u", image->path.c_str(),
            (unsigned long long)image->tick, unsigned(zone_options.epoch));
  image.reset();  // entities now live in the zone; the image is not needed any more
  log::setTag("zone " + std::to_string(node.rank()));
  std::uint64_t ticks = o.ticks ? o.ticks : std::uint64_t(std::ceil(o.duration * scene.tick_rate));
  if (ticks == 0) ticks = 300;

  MetricsWriter metrics;
  if (!o.metrics_dir.empty()) {
    std::filesystem::create_directories(o.metrics_dir);
    metrics = MetricsWriter(o.metrics_dir + "/zone_" + std::to_string(node.rank()) + ".jsonl");
  }
  zone::ZoneReport report(node);
  zone::TruthLog truth(
      o.metrics_dir.empty() ? "" : o.metrics_dir + "/truth_" + std::to_string(node.rank()) + ".csv",
      o.truth_every);
  // Only scenes with unique items have a story to tell about them.
  zone::ItemLog items(o.metrics_dir.empty() || scene.interactions.items.empty()
                          ? ""
                          : o.metrics_dir + "/zone_" + std::to_string(node.rank()) + "_items.csv");
  if (!o.restart.empty()) items.restored(node.tickCount(), node.store());
  zone::ArrivalLog arrivals(!o.arrivals.empty());
  std::unique_ptr<zone::ZoneRecorder> recorder;
  if (!o.record_dir.empty()) {
    std::filesystem::create_directories(o.record_dir);
    recorder = std::make_unique<zone::ZoneRecorder>(o.record_dir, scene, node, o.record_every,
                                                    !o.restart.empty());
  }
  ZS_INFO(
      "zone %d/%d rect [%.1f,%.1f]-[%.1f,%.1f]: %zu entities, particles on %s, flocks on "
      "%s, %llu ticks",
      node.rank(), node.size(), node.layout().rect(node.rank()).min_x,
      node.layout().rect(node.rank()).min_z, node.layout().rect(node.rank()).max_x,
      node.layout().rect(node.rank()).max_z, node.store().size(), node.particleBackend().c_str(),
      node.flockBackend().c_str(), (unsigned long long)ticks);

  Stopwatch wall;
  timespec next;
  clock_gettime(CLOCK_MONOTONIC, &next);
  while (node.tickCount() < ticks) {
    if (anyRankStopping(comm)) break;
    // The factor this tick runs at (set by the previous tick): dt stays, the period stretches.
    const double period = node.dilation().periodSeconds();
    Stopwatch tick_time;
    node.tick();
    const double tick_seconds = tick_time.elapsedSeconds();
    if (o.realtime) {
      next = addSeconds(next, period);
      report.recordPacing(node, period, isPast(next));
    }
    report.recordTick(node, tick_seconds, metrics);
    truth.record(node.tickCount() - 1, node.store());  // the tick just published
    arrivals.record(node.tickCount() - 1, node.flowArrivalsThisTick());
    // Runs stopped by a signal end on different ticks; a state compared between runs must not.
    if (!o.dump_state.empty() && node.tickCount() == o.dump_state_at)
      zone::dumpState(comm, node.store(), node.liveParticles(), o.dump_state);
    items.left(node.tickCount(), node.itemsLeftThisTick());
    if (recorder) recorder->record(node, tick_seconds);
    if (o.realtime) sleepUntil(next);
  }
  metrics.flush();
  if (recorder) recorder->close();
  std::string summary = report.summaryJson(node, wall.elapsedSeconds());
  if (!o.metrics_dir.empty()) {
    std::ofstream(o.metrics_dir + "/zone_" + std::to_string(node.rank()) + "_summary.json")
        << summary << "\n";
  }
  std::printf("%s\n", summary.c_str());
  std::fflush(stdout);
  if (!o.dump_state.empty() && o.dump_state_at == 0)
    zone::dumpState(comm, node.store(), node.liveParticles(), o.dump_state);
  if (!o.arrivals.empty()) arrivals.write(comm, o.arrivals);
  if (o.dump_state_at > node.tickCount() && node.rank() == 0)
    std::fprintf(stderr,
                 "zone_node: --dump-state-at %llu: the run stopped at tick %llu, so %s was "
                 "not written\n",
                 (unsigned long long)o.dump_state_at, (unsigned long long)node.tickCount(),
                 o.dump_state.c_str());
  const zone::ConservationTally& c = node.conservation();
  return c.failures == 0 && c.mail_failures == 0 ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  zonesim::installStopSignals();
  Options o;
  CLI::App app{"zonesim zone node: one MPI rank per zone"};
  app.add_option("--scene", o.scene, "scene file (YAML)")->required();
  app.add_option("--ticks", o.ticks,
                 "run until this tick (counted from the scene's start, also after --restart)");
  app.add_option("--duration", o.duration,
                 "seconds of simulated time to run (ticks = duration * tick rate)");
  app.add_flag("--realtime", o.realtime,
               "pace ticks at the scene's tick rate (otherwise as fast as possible)");
  app.add_option("--metrics", o.metrics_dir,
                 "folder for zone_<rank>.jsonl and zone_<rank>_summary.json");
  app.add_option("--truth-every", o.truth_every,
                 "with --metrics: write truth_<rank>.csv, the true position of every K-th "
                 "entity id each tick (for deploy/truth_error.py)");
  CLI::Option* dump_state = app.add_option("--dump-state", o.dump_state,
                                           "write every entity's final state (JSON lines) here");
  app.add_option("--dump-state-at", o.dump_state_at,
                 "with --dump-state: write it at the end of this tick (counted from the scene's "
                 "start) instead of at the end of the run; a run that stops earlier writes none")
      ->needs(dump_state);
  app.add_option("--arrivals", o.arrivals,
                 "write the tick each flow-field NPC reached its destination during this run here "
                 "(CSV id,tick in id order, at the end of the run)");
  app.add_option("--dds-domain", o.zone.dds_domain, "DDS domain id");
  bool no_dds = false;
  app.add_flag("--no-dds", no_dds, "run without DDS (no gateway can attach)");
  app.add_option("--check-every", o.zone.check_every, "ticks between conservation checks");
  app.add_option("--checkpoint-dir", o.zone.checkpoint_dir, "write checkpoints into this folder");
  app.add_option("--checkpoint-every", o.zone.checkpoint_every, "ticks between checkpoints");
  app.add_option("--balance-every", o.zone.balance.every,
                 "ticks between load-balance checks (0: boundaries stay fixed)");
  app.add_option("--balance-threshold", o.zone.balance.threshold,
                 "max/mean tick cost that starts moving boundaries")
      ->check(CLI::Range(1.0, 100.0));
  app.add_option("--balance-step", o.zone.balance.step,
                 "fraction of the way boundaries move per check")
      ->check(CLI::Range(0.01, 1.0));
  app.add_option(
      "--restart", o.restart,
      "continue from a checkpoint (a checkpoint folder, or a --checkpoint-dir: its LATEST)");
  app.add_option("--epoch", o.epoch,
                 "the cluster epoch every DDS sample carries, one more per restart (default: 0, "
                 "or 1 with --restart; a supervisor restarting again from one checkpoint must "
                 "count on)")
      ->check(CLI::Range(std::int64_t(0), std::int64_t(UINT32_MAX)));
  app.add_option("--orphan-grace", o.orphan_grace_s,
                 "seconds an avatar may go without input (its player gone with its gateway) "
                 "before the zone removes it; 0: never")
      ->check(CLI::Range(0.0, 86400.0));
  app.add_option("--gpu", o.zone.gpu,
                 "particles and flocks on OpenCL: on, off, auto (particles from a measured "
                 "default, flocks of 1,000 or more from a threshold timed on rank 0 at start and "
                 "broadcast), probe (auto with both thresholds timed) or scene (its gpu.mode; "
                 "absent: auto)")
      ->check(CLI::IsMember({"on", "off", "auto", "probe", "scene"}));
  app.add_option("--time-dilation", o.time_dilation,
                 "slow the cluster's clock under overload: on, off, or scene (its time_dilation "
                 "key; absent: off)")
      ->check(CLI::IsMember({"on", "off", "scene"}));
  app.add_option("--record", o.record_dir,
                 "write a recording of every tick into this folder (zone_<rank>.zsrec: entities, "
                 "zone rectangle, handoffs, checkpoints, tick profile) for deploy/inspect.sh");
  app.add_option("--record-every", o.record_every,
                 "with --record: record one entity id in this many (1: every entity)")
      ->check(CLI::Range(1u, 1000000u));
  app.add_option("--ledger", o.ledger,
                 "commit players' transactions here: sqlite:PATH (every rank may share one "
                 "file) or postgres:CONNINFO; without it, transactions fail with that reason")
      ->check([](const std::string& spec) {
        try {
          zonesim::ledger::parseStoreSpec(spec);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      });
  zonesim::addCommonOptions(app, o.common);
  CLI11_PARSE(app, argc, argv);
  o.zone.dds = !no_dds;
  if (!o.ledger.empty()) o.zone.ledger = zonesim::ledger::parseStoreSpec(o.ledger);
  zonesim::applyCommonOptions(o.common, "zone");

  MPI_Init(&argc, &argv);
  int rc = 1;
  try {
    rc = run(o, MPI_COMM_WORLD);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "zone_node: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  MPI_Finalize();
  return rc;
}
