// FlatIdMap against std::unordered_map: the same answers under random inserts, assignments,
// erases and sweeps, including runs that collide and wrap round the end of the table.
#include "common/flat_id_map.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <unordered_map>

#include "common/rng.h"

namespace zonesim {
namespace {

template <typename V>
void expectSame(const FlatIdMap<V>& flat, const std::unordered_map<std::uint64_t, V>& ref) {
  ASSERT_EQ(flat.size(), ref.size());
  for (const auto& [id, v] : ref) {
    const V* got = flat.find(id);
    ASSERT_NE(got, nullptr) << id;
    EXPECT_EQ(*got, v) << id;
  }
  std::size_t visited = 0;
  flat.forEach([&](std::uint64_t id, const V& v) {
    ++visited;
    auto it = ref.find(id);
    ASSERT_NE(it, ref.end()) << id;
    EXPECT_EQ(it->second, v);
  });
  EXPECT_EQ(visited, ref.size());
}

TEST(FlatIdMap, InsertFindAssignErase) {
  FlatIdMap<int> m;
  EXPECT_EQ(m.find(5), nullptr);
  EXPECT_FALSE(m.erase(5));
  auto [v, inserted] = m.tryEmplace(5, 50);
  EXPECT_TRUE(inserted);
  EXPECT_EQ(*v, 50);
  EXPECT_FALSE(m.tryEmplace(5, 99).second);  // present: kept as it was
  EXPECT_EQ(*m.find(5), 50);
  m.insertOrAssign(5, 51);
  EXPECT_EQ(*m.find(5), 51);
  EXPECT_TRUE(m.contains(5));
  EXPECT_TRUE(m.erase(5));
  EXPECT_FALSE(m.contains(5));
  EXPECT_TRUE(m.empty());
  EXPECT_THROW(m.tryEmplace(0, 1), std::invalid_argument);
}

TEST(FlatIdMap, MatchesUnorderedMapUnderRandomChurn) {
  // Ids from a small range collide often and fill long runs; sequential ids (how zones hand
  // them out) and huge ones (player-tagged) are mixed in.
  Pcg32 rng(7, 11);
  FlatIdMap<std::uint64_t> flat;
  std::unordered_map<std::uint64_t, std::uint64_t> ref;
  for (int step = 0; step < 200'000; ++step) {
    std::uint64_t id = 0;
    switch (rng.next() % 3) {
      case 0: id = 1 + rng.next() % 300; break;
      case 1: id = 1000 + std::uint64_t(step % 500); break;
      default: id = (std::uint64_t{0xABCD} << 48) | (rng.next() % 2000); break;
    }
    std::uint64_t value = rng.next();
    switch (rng.next() % 4) {
      case 0:
        EXPECT_EQ(flat.tryEmplace(id, value).second, ref.try_emplace(id, value).second);
        break;
      case 1:
        flat.insertOrAssign(id, value);
        ref[id] = value;
        break;
      default:
        EXPECT_EQ(flat.erase(id), ref.erase(id) == 1);
        break;
    }
    if (step % 20'000 == 0) expectSame(flat, ref);
  }
  expectSame(flat, ref);
}

TEST(FlatIdMap, EraseIfRemovesExactlyWhatItSelects) {
  Pcg32 rng(3, 4);
  for (int round = 0; round < 50; ++round) {
    FlatIdMap<int> flat;
    std::unordered_map<std::uint64_t, int> ref;
    for (int i = 0; i < 200; ++i) {
      std::uint64_t id = 1 + rng.next() % 1000;
      int v = int(rng.next() % 10);
      flat.insertOrAssign(id, v);
      ref[id] = v;
    }
    // Each selected entry is seen (and removed) once; kept ones may be seen again.
    std::size_t removed = 0;
    flat.eraseIf([&](std::uint64_t, const int& v) {
      if (v >= 5) ++removed;
      return v >= 5;
    });
    std::size_t selected = std::erase_if(ref, [](const auto& kv) { return kv.second >= 5; });
    expectSame(flat, ref);
    EXPECT_EQ(removed, selected);
  }
}

TEST(FlatIdMap, ClearKeepsItUsable) {
  FlatIdMap<int> m;
  for (std::uint64_t id = 1; id <= 100; ++id) m.tryEmplace(id, int(id));
  m.clear();
  EXPECT_TRUE(m.empty());
  EXPECT_EQ(m.find(7), nullptr);
  m.tryEmplace(7, 70);
  EXPECT_EQ(*m.find(7), 70);
}

}  // namespace
}  // namespace zonesim
