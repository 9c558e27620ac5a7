#pragma once
// The conformance suite every LedgerStore back end passes (store_conformance.cpp), written
// once and instantiated per back end: sqlite_store_test.cpp, postgres_store_test.cpp.

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <ostream>
#include <string>

#include "ledger/store.h"

namespace zonesim::ledger::test {

/// One test's database: fresh and empty when made, removed when destroyed.
class StoreHarness {
 public:
  virtual ~StoreHarness() = default;
  /// Opens (again) this test's database: a new connection each time, as after a restart.
  virtual std::unique_ptr<LedgerStore> open() = 0;
};

struct BackendParam {
  std::string name;
  std::function<std::unique_ptr<StoreHarness>()> make;
};

inline void PrintTo(const BackendParam& param, std::ostream* os) {
  *os << param.name;
}

inline std::string backendName(const ::testing::TestParamInfo<BackendParam>& info) {
  return info.param.name;
}

class StoreConformance : public ::testing::TestWithParam<BackendParam> {
 protected:
  void SetUp() override {
    ASSERT_NO_THROW(harness_ = GetParam().make()) << "cannot make the test database";
    ASSERT_NO_THROW(store_ = harness_->open());
  }
  void TearDown() override {
    store_.reset();
    harness_.reset();
  }
  std::unique_ptr<StoreHarness> harness_;
  std::unique_ptr<LedgerStore> store_;
};

/// A valid transaction of `kind` with fields derived from the key, so tests read short.
Transaction makeTx(std::uint64_t player, std::uint64_t seq, Kind kind = Kind::Loot);
/// A score of `score` at `tick`.
Transaction makeScore(std::uint64_t player, std::uint64_t seq, std::int64_t score,
                      std::uint64_t tick);

}  // namespace zonesim::ledger::test
