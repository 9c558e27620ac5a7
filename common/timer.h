#pragma once
// Monotonic timing: a stopwatch, and a per-tick profile of named phases.

#include <time.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <string_view>

namespace zonesim {

/// Nanoseconds on the steady clock.
inline std::int64_t nowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// CPU time this thread has used, in nanoseconds: unlike wall time it does not grow while the
/// thread waits or is descheduled (oversubscribed ranks), so it measures work done.
inline std::int64_t threadCpuNs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return std::int64_t(t.tv_sec) * 1000000000 + t.tv_nsec;
}

/// CPU time the whole process (every thread) has used, in nanoseconds.
inline std::int64_t processCpuNs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return std::int64_t(t.tv_sec) * 1000000000 + t.tv_nsec;
}

/// Microseconds since the Unix epoch (wall clock, for timestamps shared between processes).
inline std::uint64_t wallTimeUs() {
  return std::uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count());
}

class Stopwatch {
 public:
  Stopwatch() : start_(nowNs()) {}
  void restart() { start_ = nowNs(); }
  std::int64_t elapsedNs() const { return nowNs() - start_; }
  double elapsedSeconds() const { return double(elapsedNs()) * 1e-9; }

 private:
  std::int64_t start_;
};

/// Seconds spent in each phase of one tick; Phase indexes the array.
template <typename Phase, std::size_t N>
struct PhaseProfile {
  std::array<double, N> seconds{};
  double& operator[](Phase p) { return seconds[std::size_t(p)]; }
  double operator[](Phase p) const { return seconds[std::size_t(p)]; }
  double total() const {
    double t = 0;
    for (double s : seconds) t += s;
    return t;
  }
};

/// Adds the time of its scope to a slot.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& slot) : slot_(slot), start_(nowNs()) {}
  ~ScopedTimer() { slot_ += double(nowNs() - start_) * 1e-9; }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& slot_;
  std::int64_t start_;
};

}  // namespace zonesim
