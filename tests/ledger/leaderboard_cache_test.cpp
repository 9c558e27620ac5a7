// The zone's leaderboard reader: nothing before its first reading, then the top rows as the
// ledger holds them; new scores show once `refresh` has passed and someone asks again; one
// reading per refresh however often it is asked; a failed reading keeps the last good rows
// and says why.
#include "ledger/leaderboard_cache.h"

#include <gtest/gtest.h>

#include <sqlite3.h>

#include "committer_support.h"
#include "store_conformance.h"
#include "temp_dir.h"

namespace zonesim::ledger::test {
namespace {

using namespace std::chrono_literals;

LeaderboardSnapshot waitForReading(LeaderboardCache& cache, std::uint64_t after) {
  LeaderboardSnapshot s;
  EXPECT_TRUE(waitUntil([&] { return (s = cache.latest()).readings > after; }));
  return s;
}

TEST(LeaderboardCache, ServesTheLedgersTopAndRereadsAtMostOncePerRefresh) {
  TempDir dir;
  auto writer = openStore({.backend = "sqlite", .target = dir.file("l.db")});
  std::vector<Transaction> scores{makeScore(1, 1, 500, 10), makeScore(2, 1, 900, 11),
                                  makeScore(3, 1, 700, 12)};
  writer->commit(scores);
  LeaderboardCache cache(openStore({.backend = "sqlite", .target = dir.file("l.db")}), 2, 200ms);
  LeaderboardSnapshot s = waitForReading(cache, 0);
  EXPECT_EQ(s.rows, (std::vector<LeaderboardRow>{{2, 900, 11}, {3, 700, 12}}));
  EXPECT_EQ(s.error, "");
  Transaction better = makeScore(1, 2, 1000, 13);
  writer->commit({&better, 1});
  // Asked a hundred times within the refresh: still one reading, then the new top.
  for (int i = 0; i < 100; ++i) EXPECT_LE(cache.latest().readings, 2u);
  s = waitForReading(cache, 1);
  EXPECT_EQ(s.rows.front(), (LeaderboardRow{1, 1000, 13}));
}

TEST(LeaderboardCache, AFailedReadingKeepsTheLastRowsAndSaysWhy) {
  TempDir dir;
  auto writer = openStore({.backend = "sqlite", .target = dir.file("l.db")});
  Transaction t = makeScore(4, 1, 300, 5);
  writer->commit({&t, 1});
  LeaderboardCache cache(openStore({.backend = "sqlite", .target = dir.file("l.db")}), 5, 50ms);
  LeaderboardSnapshot s = waitForReading(cache, 0);
  ASSERT_EQ(s.rows.size(), 1u);
  // Someone drops the ledger's table: the next reading fails.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(dir.file("l.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "DROP TABLE ledger_tx", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  ASSERT_TRUE(waitUntil([&] { return !(s = cache.latest()).error.empty(); }));
  EXPECT_NE(s.error.find("leaderboard"), std::string::npos) << s.error;
  EXPECT_EQ(s.rows, (std::vector<LeaderboardRow>{{4, 300, 5}})) << "the last good rows stay";
}

}  // namespace
}  // namespace zonesim::ledger::test
