#pragma once
// Readiness of many sockets at once, with epoll: poll() passes over every descriptor on every
// call, so a process watching 2,000 player sockets paid for 2,000 on each wake-up; an epoll
// wait costs only the ones that are ready. Level-triggered: a socket still holding datagrams is
// reported again, so a reader may stop at a batch and come back.

#include <sys/epoll.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace zonesim::gateway {

class EpollSet {
 public:
  /// Sockets reported by one wait at most; the rest stay ready for the next.
  static constexpr std::size_t kMaxEvents = 256;

  /// Throws std::system_error if the kernel gives no epoll instance.
  EpollSet();
  ~EpollSet();
  EpollSet(EpollSet&& other) noexcept;
  EpollSet& operator=(EpollSet&& other) noexcept;
  EpollSet(const EpollSet&) = delete;
  EpollSet& operator=(const EpollSet&) = delete;

  /// Watches fd for input; a wait reports it by key. Throws std::system_error.
  void add(int fd, std::uint64_t key);
  /// Stops watching fd (which must be watched). Throws std::system_error.
  void remove(int fd);
  /// Waits until a watched fd is readable (or has an error to read) or the steady clock reaches
  /// deadline_ns (timeoutMsUntil: never early). Returns how many are ready, their keys in
  /// key(0..n-1): 0 on timeout or a signal. Throws std::system_error on other errors.
  int wait(std::int64_t deadline_ns);
  /// The key of ready socket i of the last wait.
  std::uint64_t key(int i) const { return events_[std::size_t(i)].data.u64; }

 private:
  void close();
  int fd_ = -1;
  std::vector<epoll_event> events_;
};

}  // namespace zonesim::gateway
