// The fleet's open-file limit: a soft limit below what is needed is raised (and never lowered),
// and a need past the hard limit is refused with both figures in the message.
#include "clients/fd_limit.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <string>

namespace zonesim::clients {
namespace {

rlimit current() {
  rlimit lim{};
  EXPECT_EQ(::getrlimit(RLIMIT_NOFILE, &lim), 0);
  return lim;
}

// Puts the soft limit back as it was, for the tests after this one in the same process.
struct RestoreSoftLimit {
  rlimit saved = current();
  ~RestoreSoftLimit() { ::setrlimit(RLIMIT_NOFILE, &saved); }
};

TEST(FdLimit, RaisesALowSoftLimitAndNeverLowersIt) {
  RestoreSoftLimit restore;
  constexpr std::size_t kPlayers = 1200;
  std::size_t needed = fleetDescriptors(kPlayers);
  EXPECT_GT(needed, kPlayers);
  if (restore.saved.rlim_max < needed) GTEST_SKIP() << "hard limit " << restore.saved.rlim_max;
  rlimit low = restore.saved;
  low.rlim_cur = 1024;  // the usual default, below what 1,200 players need
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &low), 0);

  raiseFdLimit(needed);
  EXPECT_EQ(current().rlim_cur, rlim_t(needed));
  EXPECT_EQ(current().rlim_max, restore.saved.rlim_max);
  raiseFdLimit(100);
  EXPECT_EQ(current().rlim_cur, rlim_t(needed));
}

TEST(FdLimit, PastTheHardLimitIsRefusedNamingIt) {
  RestoreSoftLimit restore;
  if (restore.saved.rlim_max == RLIM_INFINITY) GTEST_SKIP() << "no hard limit here";
  auto needed = std::size_t(restore.saved.rlim_max) + 1;
  try {
    raiseFdLimit(needed);
    FAIL() << "no FdLimitError";
  } catch (const FdLimitError& e) {
    EXPECT_EQ(e.needed(), needed);
    EXPECT_EQ(e.hard(), std::uint64_t(restore.saved.rlim_max));
    std::string what = e.what();
    EXPECT_NE(what.find(std::to_string(restore.saved.rlim_max)), std::string::npos) << what;
    EXPECT_NE(what.find("RLIMIT_NOFILE"), std::string::npos) << what;
  }
  EXPECT_EQ(current().rlim_cur, restore.saved.rlim_cur);
}

}  // namespace
}  // namespace zonesim::clients
