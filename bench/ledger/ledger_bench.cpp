// ledger_bench [SECONDS_PER_CASE]: durable transactions, SQLite against PostgreSQL.
//
// 1. Store: commit() of batches of 1, 16 and 256 new transactions back to back for a fixed
//    time per case: committed transactions per second and the latency of one commit() call
//    (p50, p99). SQLite runs with synchronous=FULL (the default: every commit fsyncs the WAL)
//    and, for the price of that, NORMAL. PostgreSQL is a real server from Debian's package
//    (fsync on, synchronous_commit on) on a Unix socket, started in a temporary folder.
// 2. Tick: a thread with a 33 ms period does 8 ms of fixed arithmetic per tick and submits
//    200 transactions per tick to a LedgerCommitter (polling outcomes each tick); its own time
//    per tick (work + submit + poll) p50/p99 with the committer against without, and the
//    submit-to-outcome latency. The zone integration comes later: this is the committer's
//    effect on a thread shaped like the tick, on the same cores.
//
// Files go under TMPDIR (the SQLite file, the PostgreSQL data folder); say which disk.

#include <sys/statfs.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "ledger/committer.h"
#include "ledger/postgres_store.h"
#include "ledger/sqlite_store.h"
#include "pg_server.h"

namespace {

using namespace zonesim::ledger;
using Clock = std::chrono::steady_clock;

double ms(Clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  std::size_t i = std::size_t(std::ceil(p * double(v.size()))) - 1;
  return v[std::min(i, v.size() - 1)];
}

struct StoreFigures {
  double tx_per_s = 0, p50_ms = 0, p99_ms = 0;
  std::size_t commits = 0;
};

Transaction txOf(std::uint64_t player, std::uint64_t seq, std::uint64_t tick) {
  Transaction tx;
  tx.player = player;
  tx.seq = seq;
  tx.kind = seq % 4 == 0 ? Kind::Score : Kind::Purchase;
  tx.item = 100 + seq % 13;
  tx.amount = 1;
  tx.price = 25;
  tx.score = std::int64_t(seq * 7 % 1000);
  tx.tick = tick;
  return tx;
}

StoreFigures runStore(LedgerStore& store, std::size_t batch_size, double seconds) {
  std::vector<double> latencies;
  std::vector<Transaction> batch(batch_size);
  std::uint64_t seq = 0, committed = 0;
  const auto start = Clock::now();
  const auto until = start + std::chrono::duration<double>(seconds);
  while (Clock::now() < until) {
    for (auto& tx : batch) {
      ++seq;
      tx = txOf(1 + seq % 1000, 1 + seq / 1000, seq);
    }
    auto t0 = Clock::now();
    auto results = store.commit(batch);
    latencies.push_back(ms(Clock::now() - t0));
    for (const auto& r : results) committed += r.status == TxStatus::Committed;
  }
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  return {double(committed) / elapsed, percentile(latencies, 0.5), percentile(latencies, 0.99),
          latencies.size()};
}

struct TickFigures {
  double p50_ms = 0, p99_ms = 0, max_ms = 0;
  double outcome_p50_ms = 0, outcome_p99_ms = 0;
  std::size_t committed = 0, full = 0;
};

// A fixed amount of arithmetic, about `target_ms` on this machine when measured alone.
double busyWork(std::size_t iterations) {
  double x = 1.0;
  for (std::size_t i = 0; i < iterations; ++i) x = x * 1.0000001 + 1e-9;
  return x;
}

std::size_t calibrate(double target_ms) {
  std::size_t n = 1'000'000;
  for (;;) {
    auto t0 = Clock::now();
    volatile double sink = busyWork(n);
    (void)sink;
    double took = ms(Clock::now() - t0);
    if (took > 2.0) return std::size_t(double(n) * target_ms / took);
    n *= 4;
  }
}

// `committer` may be null: the baseline tick without one.
TickFigures runTicks(LedgerCommitter* committer, std::size_t work, int ticks, int per_tick) {
  TickFigures f;
  std::vector<double> own, outcome_ms;
  std::vector<Clock::time_point> submitted;  // indexed by seq - 1 (one player)
  submitted.reserve(std::size_t(ticks * per_tick));
  std::vector<Outcome> outcomes;
  outcomes.reserve(8192);
  std::uint64_t seq = 0;
  const auto period = std::chrono::milliseconds(33);
  auto next = Clock::now() + period;
  for (int t = 0; t < ticks; ++t) {
    std::this_thread::sleep_until(next);
    next += period;
    auto t0 = Clock::now();
    volatile double sink = busyWork(work);
    (void)sink;
    if (committer) {
      for (int i = 0; i < per_tick; ++i) {
        Transaction tx = txOf(1 + seq % 500, 1 + seq / 500, std::uint64_t(t));
        if (committer->submit(tx) == Submit::Accepted) {
          submitted.push_back(Clock::now());
          ++seq;
        } else {
          ++f.full;
        }
      }
      outcomes.clear();
      committer->poll(outcomes);
      auto now = Clock::now();
      for (const auto& o : outcomes) {
        std::uint64_t index = (o.tx.seq - 1) * 500 + (o.tx.player - 1);
        outcome_ms.push_back(ms(now - submitted[index]));
        f.committed += o.status == TxStatus::Committed;
      }
    }
    own.push_back(ms(Clock::now() - t0));
  }
  if (committer) {
    // Drain, so every transaction counts.
    auto until = Clock::now() + std::chrono::seconds(60);
    while (committer->inFlight() > 0 && Clock::now() < until) {
      outcomes.clear();
      if (committer->poll(outcomes) == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      for (const auto& o : outcomes) f.committed += o.status == TxStatus::Committed;
    }
  }
  f.p50_ms = percentile(own, 0.5);
  f.p99_ms = percentile(own, 0.99);
  f.max_ms = percentile(own, 1.0);
  f.outcome_p50_ms = percentile(outcome_ms, 0.5);
  f.outcome_p99_ms = percentile(outcome_ms, 0.99);
  return f;
}

std::string fsType(const std::string& path) {
  struct statfs s {};
  if (statfs(path.c_str(), &s) != 0) return "unknown";
  switch (s.f_type) {
    case 0xEF53:
      return "ext4";
    case 0x01021994:
      return "tmpfs";
    case 0x794c7630:
      return "overlayfs";
    case 0x58465342:
      return "xfs";
    case 0x9123683E:
      return "btrfs";
    default:
      return "0x" + std::to_string(s.f_type);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 3.0;
  namespace fs = std::filesystem;
  std::string tmpl = (fs::temp_directory_path() / "zonesim-ledger-bench-XXXXXX").string();
  if (!mkdtemp(tmpl.data())) {
    std::fprintf(stderr, "ledger_bench: cannot make a folder under %s\n",
                 fs::temp_directory_path().c_str());
    return 1;
  }
  const fs::path dir = tmpl;
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup{dir};
  std::printf("ledger_bench: %.1f s per case, files in %s (%s), %u hardware threads\n", seconds,
              dir.c_str(), fsType(dir.string()).c_str(), std::thread::hardware_concurrency());

  std::unique_ptr<zonesim::ledger::test::PgServer> server;
  try {
    server = std::make_unique<zonesim::ledger::test::PgServer>();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ledger_bench: cannot start PostgreSQL: %s\n", e.what());
    return 1;
  }
  server->createDatabase("bench_store");
  server->createDatabase("bench_tick");

  const std::size_t batches[] = {1, 16, 256};
  struct Row {
    std::string backend;
    std::size_t batch;
    StoreFigures f;
  };
  std::vector<Row> rows;
  int case_index = 0;
  auto sqlite = [&](bool full) {
    return std::make_unique<SqliteStore>(
        SqliteOptions{.path = (dir / ("store_" + std::to_string(case_index++) + ".db")).string(),
                      .synchronous_full = full});
  };
  std::printf("\n%-26s %6s %12s %9s %10s %10s\n", "store", "batch", "tx/s", "commits", "p50 ms",
              "p99 ms");
  for (std::size_t b : batches) {
    for (int which = 0; which < 3; ++which) {
      std::unique_ptr<LedgerStore> store;
      std::string name;
      if (which == 0) {
        store = sqlite(true), name = "sqlite synchronous=FULL";
      } else if (which == 1) {
        store = sqlite(false), name = "sqlite synchronous=NORMAL";
      } else {
        // A fresh database per batch size: the same key range is reused.
        std::string db = "bench_b" + std::to_string(b);
        server->createDatabase(db);
        store = std::make_unique<PostgresStore>(PostgresOptions{.conninfo = server->conninfo(db)});
        name = "postgres";
      }
      StoreFigures f = runStore(*store, b, seconds);
      std::printf("%-26s %6zu %12.0f %9zu %10.3f %10.3f\n", name.c_str(), b, f.tx_per_s, f.commits,
                  f.p50_ms, f.p99_ms);
      std::fflush(stdout);
      rows.push_back({name, b, f});
    }
  }
  std::printf("\nratio sqlite FULL / postgres, tx/s:");
  for (std::size_t i = 0; i + 2 < rows.size(); i += 3) {
    std::printf("  batch %zu: %.2f", rows[i].batch, rows[i].f.tx_per_s / rows[i + 2].f.tx_per_s);
  }
  std::printf("\n");

  // 2. The tick.
  const int ticks = int(seconds * 30 * 2);
  const int per_tick = 200;
  const std::size_t work = calibrate(8.0);
  std::printf("\ntick: 33 ms period, 8 ms of arithmetic, %d submissions per tick, %d ticks\n",
              per_tick, ticks);
  std::printf("%-26s %9s %9s %9s %12s %12s %10s\n", "committer", "p50 ms", "p99 ms", "max ms",
              "outcome p50", "outcome p99", "committed");
  auto printTick = [](const char* name, const TickFigures& f) {
    std::printf("%-26s %9.3f %9.3f %9.3f %12.3f %12.3f %10zu%s\n", name, f.p50_ms, f.p99_ms,
                f.max_ms, f.outcome_p50_ms, f.outcome_p99_ms, f.committed,
                f.full ? " (some Full)" : "");
  };
  printTick("none", runTicks(nullptr, work, ticks, per_tick));
  {
    LedgerCommitter c(sqlite(true), {.capacity = 8192});
    printTick("sqlite synchronous=FULL", runTicks(&c, work, ticks, per_tick));
  }
  {
    LedgerCommitter c(std::make_unique<PostgresStore>(
                          PostgresOptions{.conninfo = server->conninfo("bench_tick")}),
                      {.capacity = 8192});
    printTick("postgres", runTicks(&c, work, ticks, per_tick));
  }
  return 0;
}
