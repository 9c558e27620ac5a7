#pragma once
// What the committer tests share: waiting for outcomes, or for a condition, with a generous
// deadline (never a timing assertion).

#include <chrono>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "ledger/committer.h"

namespace zonesim::ledger::test {

/// Polls until `n` outcomes arrived in `out` or 60 s passed; returns whether they did.
inline bool waitForOutcomes(LedgerCommitter& committer, std::vector<Outcome>& out, std::size_t n) {
  auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (out.size() < n) {
    if (committer.poll(out) == 0) {
      if (std::chrono::steady_clock::now() > until) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
  return true;
}

/// Waits up to 60 s for `condition`; returns whether it held.
inline bool waitUntil(const std::function<bool()>& condition) {
  auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!condition()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

}  // namespace zonesim::ledger::test
