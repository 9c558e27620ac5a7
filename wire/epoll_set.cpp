#include "wire/epoll_set.h"

#include <unistd.h>

#include <cerrno>
#include <system_error>
#include <utility>

#include "wire/udp_socket.h"

namespace zonesim::gateway {

namespace {
[[noreturn]] void throwErrno(const char* what) {
  throw std::system_error(errno, std::generic_category(), what);
}
}  // namespace

EpollSet::EpollSet() : events_(kMaxEvents) {
  fd_ = ::epoll_create1(EPOLL_CLOEXEC);
  if (fd_ < 0) throwErrno("epoll_create1");
}

EpollSet::~EpollSet() {
  close();
}

EpollSet::EpollSet(EpollSet&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), events_(std::move(other.events_)) {}

EpollSet& EpollSet::operator=(EpollSet&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = std::exchange(other.fd_, -1);
    events_ = std::move(other.events_);
  }
  return *this;
}

void EpollSet::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void EpollSet::add(int fd, std::uint64_t key) {
  epoll_event e{};
  e.events = EPOLLIN;
  e.data.u64 = key;
  if (::epoll_ctl(fd_, EPOLL_CTL_ADD, fd, &e) != 0) throwErrno("epoll_ctl add");
}

void EpollSet::remove(int fd) {
  if (::epoll_ctl(fd_, EPOLL_CTL_DEL, fd, nullptr) != 0) throwErrno("epoll_ctl del");
}

int EpollSet::wait(std::int64_t deadline_ns) {
  int n = ::epoll_wait(fd_, events_.data(), int(events_.size()), timeoutMsUntil(deadline_ns));
  if (n < 0 && errno != EINTR) throwErrno("epoll_wait");
  return n < 0 ? 0 : n;
}

}  // namespace zonesim::gateway
