// GenerationalPool: handles to freed and reused slots stop resolving; iteration is in slot
// order so simulations that walk the pool stay deterministic.

#include "common/generational_pool.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace zonesim {
namespace {

TEST(GenerationalPool, StaleHandleStopsResolvingAfterEraseAndReuse) {
  GenerationalPool<std::string> pool;
  SlotHandle a = pool.insert("a");
  SlotHandle b = pool.insert("b");
  ASSERT_NE(pool.get(a), nullptr);
  EXPECT_EQ(*pool.get(a), "a");

  EXPECT_TRUE(pool.erase(a));
  EXPECT_EQ(pool.get(a), nullptr);
  EXPECT_FALSE(pool.erase(a));  // a second erase through the stale handle does nothing

  SlotHandle c = pool.insert("c");
  EXPECT_EQ(c.index, a.index);  // the slot is reused...
  EXPECT_NE(c.generation, a.generation);
  EXPECT_EQ(pool.get(a), nullptr);  // ...but the old handle does not see the new value
  ASSERT_NE(pool.get(c), nullptr);
  EXPECT_EQ(*pool.get(c), "c");
  EXPECT_EQ(*pool.get(b), "b");
  EXPECT_EQ(pool.size(), 2u);

  const auto& const_pool = pool;
  EXPECT_EQ(const_pool.get(a), nullptr);
  EXPECT_EQ(*const_pool.get(c), "c");
}

TEST(GenerationalPool, HandleOutOfRangeDoesNotResolve) {
  GenerationalPool<int> pool;
  EXPECT_EQ(pool.get(SlotHandle{5, 1}), nullptr);
  pool.insert(1);
  EXPECT_EQ(pool.get(SlotHandle{}), nullptr);  // default handle: generation 0 is never issued
}

TEST(GenerationalPool, PackedHandleRoundTrips) {
  SlotHandle h{123456, 0xdeadbeef};
  EXPECT_EQ(SlotHandle::unpack(h.packed()), h);
}

TEST(GenerationalPool, ForEachVisitsLiveSlotsInIndexOrder) {
  GenerationalPool<int> pool;
  std::vector<SlotHandle> handles;
  for (int i = 0; i < 6; ++i) handles.push_back(pool.insert(i * 10));
  pool.erase(handles[4]);
  pool.erase(handles[1]);
  SlotHandle reused = pool.insert(99);  // fills slot 1, the last freed
  EXPECT_EQ(reused.index, 1u);

  std::vector<std::uint32_t> indices;
  std::vector<int> values;
  pool.forEach([&](SlotHandle h, int& v) {
    indices.push_back(h.index);
    values.push_back(v);
    EXPECT_EQ(pool.get(h), &v);
  });
  EXPECT_EQ(indices, (std::vector<std::uint32_t>{0, 1, 2, 3, 5}));
  EXPECT_EQ(values, (std::vector<int>{0, 99, 20, 30, 50}));
}

}  // namespace
}  // namespace zonesim
