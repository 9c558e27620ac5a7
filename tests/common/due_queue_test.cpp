// DueQueue against a plain scan of every item's due time: the same earliest time and the same
// items popped, in (due, item) order, under random arming, re-arming earlier and later, and
// disarming; the fleet relies on a re-armed item moving both ways.
#include "common/due_queue.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "common/rng.h"

namespace zonesim {
namespace {

TEST(DueQueue, PopsEarliestFirstAndEqualTimesInItemOrder) {
  DueQueue q(5);
  q.arm(3, 20);
  q.arm(1, 10);
  q.arm(4, 10);
  q.arm(0, 30);
  EXPECT_EQ(q.size(), 4u);
  EXPECT_FALSE(q.armed(2));
  EXPECT_EQ(q.due(2), INT64_MAX);
  EXPECT_EQ(q.nextDue(), 10);
  std::vector<std::size_t> out;
  q.popDue(20, out);
  EXPECT_EQ(out, (std::vector<std::size_t>{1, 4, 3}));
  EXPECT_FALSE(q.armed(1));
  EXPECT_EQ(q.nextDue(), 30);
  out.clear();
  q.popDue(29, out);
  EXPECT_TRUE(out.empty());
  q.popDue(30, out);
  EXPECT_EQ(out, (std::vector<std::size_t>{0}));
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.nextDue(), INT64_MAX);
}

TEST(DueQueue, ReArmingMovesAnItemEarlierOrLater) {
  DueQueue q(3);
  q.arm(0, 100);
  q.arm(1, 200);
  q.arm(2, 300);
  q.arm(2, 50);  // earlier: now first
  EXPECT_EQ(q.nextDue(), 50);
  q.arm(2, 400);  // later: last again
  q.arm(0, 250);
  EXPECT_EQ(q.size(), 3u);
  EXPECT_EQ(q.due(0), 250);
  std::vector<std::size_t> out;
  q.popDue(1000, out);
  EXPECT_EQ(out, (std::vector<std::size_t>{1, 0, 2}));
}

TEST(DueQueue, DisarmTakesAnItemOutWhereverItIs) {
  DueQueue q(4);
  for (std::size_t i = 0; i < 4; ++i) q.arm(i, std::int64_t(10 * (i + 1)));
  q.disarm(0);  // the root
  q.disarm(3);  // the last slot
  q.disarm(3);  // twice: nothing
  EXPECT_EQ(q.size(), 2u);
  EXPECT_EQ(q.nextDue(), 20);
  std::vector<std::size_t> out;
  q.popDue(INT64_MAX, out);
  EXPECT_EQ(out, (std::vector<std::size_t>{1, 2}));
}

TEST(DueQueue, AgreesWithAScanUnderRandomUse) {
  constexpr std::size_t kItems = 97;
  DueQueue q(kItems);
  std::vector<std::int64_t> ref(kItems, INT64_MAX);  // INT64_MAX: not armed
  Pcg32 rng(7, 3);
  std::int64_t now = 0;
  for (int step = 0; step < 20000; ++step) {
    std::size_t item = rng.next() % kItems;
    std::uint32_t what = rng.next() % 10;
    if (what < 6) {
      // Due times in a narrow window, so that ties are common.
      std::int64_t due = now + std::int64_t(rng.next() % 50);
      q.arm(item, due);
      ref[item] = due;
    } else if (what < 8) {
      q.disarm(item);
      ref[item] = INT64_MAX;
    } else {
      now += std::int64_t(rng.next() % 20);
      std::vector<std::size_t> got;
      q.popDue(now, got);
      std::vector<std::pair<std::int64_t, std::size_t>> want;
      for (std::size_t i = 0; i < kItems; ++i)
        if (ref[i] <= now) want.emplace_back(ref[i], i);
      std::sort(want.begin(), want.end());
      ASSERT_EQ(got.size(), want.size()) << "step " << step;
      for (std::size_t k = 0; k < got.size(); ++k) {
        EXPECT_EQ(got[k], want[k].second) << "step " << step;
        ref[got[k]] = INT64_MAX;
      }
    }
    ASSERT_EQ(q.nextDue(), *std::min_element(ref.begin(), ref.end())) << "step " << step;
    ASSERT_EQ(q.size(), std::size_t(std::count_if(ref.begin(), ref.end(),
                                                  [](std::int64_t d) { return d != INT64_MAX; })));
  }
}

TEST(DueQueue, RejectsAnItemOutOfRange) {
  DueQueue q(2);
  EXPECT_THROW(q.arm(2, 0), std::out_of_range);
  EXPECT_THROW(q.disarm(5), std::out_of_range);
}

}  // namespace
}  // namespace zonesim
