#include "ledger/leaderboard_cache.h"

namespace zonesim::ledger {

LeaderboardCache::LeaderboardCache(std::unique_ptr<LedgerStore> store, std::size_t rows,
                                   std::chrono::milliseconds refresh)
    : store_(std::move(store)), rows_(rows), refresh_(refresh) {
  worker_ = std::thread([this] { run(); });
}

LeaderboardCache::~LeaderboardCache() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  cv_.notify_all();
  worker_.join();
}

LeaderboardSnapshot LeaderboardCache::latest() {
  std::lock_guard lock(mutex_);
  if (!wanted_) {
    wanted_ = true;
    cv_.notify_one();
  }
  return snapshot_;
}

void LeaderboardCache::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    cv_.wait(lock, [this] { return stopping_ || wanted_; });
    if (stopping_) return;
    wanted_ = false;
    lock.unlock();
    LeaderboardSnapshot fresh;
    try {
      fresh.rows = store_->leaderboard(rows_);
    } catch (const StoreError& e) {
      fresh.error = std::string("leaderboard: ") + e.what();
    }
    lock.lock();
    fresh.readings = snapshot_.readings + 1;
    if (!fresh.error.empty()) fresh.rows = snapshot_.rows;  // the last good one stays
    snapshot_ = std::move(fresh);
    // At most one reading per refresh, however many ask meanwhile.
    if (cv_.wait_for(lock, refresh_, [this] { return stopping_; })) return;
  }
}

}  // namespace zonesim::ledger
