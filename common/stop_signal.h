#pragma once
// SIGINT/SIGTERM as a stop request that event loops poll: installed without SA_RESTART, so a
// blocking poll() or sleep returns EINTR and the loop sees the request at once.

#include <signal.h>

#include <atomic>

namespace zonesim {

/// Set once SIGINT or SIGTERM arrived (after installStopSignals()).
inline std::atomic<bool>& stopRequested() {
  static std::atomic<bool> stop{false};
  return stop;
}

/// Routes SIGINT and SIGTERM to stopRequested(); call first thing in main().
inline void installStopSignals() {
  struct sigaction sa {};
  sa.sa_handler = [](int) { stopRequested().store(true); };
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

}  // namespace zonesim
