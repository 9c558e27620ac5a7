#pragma once
// The leaderboard as the zone serves it: a query on the ledger (LedgerStore::leaderboard, best
// score per player), run by a worker thread on its own connection, at most once per `refresh`
// and only while someone asks, so the tick never waits for the database and a thousand players
// asking cost one query a second. latest() hands out the newest snapshot.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "ledger/store.h"

namespace zonesim::ledger {

/// One reading of the leaderboard.
struct LeaderboardSnapshot {
  std::vector<LeaderboardRow> rows;
  std::string error;         ///< why the last reading failed ("" if it did not)
  std::uint64_t readings = 0;  ///< how many readings were made; 0: none yet
};

class LeaderboardCache {
 public:
  /// rows: the top this many are read; refresh: the least time between two readings.
  LeaderboardCache(std::unique_ptr<LedgerStore> store, std::size_t rows,
                   std::chrono::milliseconds refresh = std::chrono::milliseconds(1000));
  ~LeaderboardCache();
  LeaderboardCache(const LeaderboardCache&) = delete;
  LeaderboardCache& operator=(const LeaderboardCache&) = delete;

  /// The newest snapshot, without waiting; asking makes the worker read again once `refresh`
  /// has passed since its last reading.
  LeaderboardSnapshot latest();

 private:
  void run();

  std::unique_ptr<LedgerStore> store_;
  std::size_t rows_;
  std::chrono::milliseconds refresh_;
  std::mutex mutex_;
  std::condition_variable cv_;
  LeaderboardSnapshot snapshot_;
  bool wanted_ = false, stopping_ = false;
  std::thread worker_;
};

}  // namespace zonesim::ledger
