#include "clients/fd_limit.h"

#include <sys/resource.h>

#include <cerrno>
#include <string>
#include <system_error>

namespace zonesim::clients {

namespace {
// Three standard streams, the epoll set, the metrics file and the file being written at the
// end, a resolver's socket for --gateway HOST: 32 leaves room without counting them exactly.
constexpr std::size_t kSpareDescriptors = 32;
}  // namespace

FdLimitError::FdLimitError(std::size_t needed, std::uint64_t hard)
    : std::runtime_error(std::to_string(needed) + " file descriptors needed, above the hard " +
                         "limit of " + std::to_string(hard) + " (RLIMIT_NOFILE)"),
      needed_(needed),
      hard_(hard) {}

std::size_t fleetDescriptors(std::size_t players) {
  return players + kSpareDescriptors;
}

void raiseFdLimit(std::size_t needed) {
  rlimit lim{};
  if (::getrlimit(RLIMIT_NOFILE, &lim) != 0)
    throw std::system_error(errno, std::generic_category(), "getrlimit(RLIMIT_NOFILE)");
  auto want = rlim_t(needed);
  // RLIM_INFINITY is the largest rlim_t, so it passes both comparisons as unlimited.
  if (lim.rlim_cur >= want) return;
  if (lim.rlim_max < want) throw FdLimitError(needed, std::uint64_t(lim.rlim_max));
  lim.rlim_cur = want;
  if (::setrlimit(RLIMIT_NOFILE, &lim) != 0)
    throw std::system_error(errno, std::generic_category(), "setrlimit(RLIMIT_NOFILE)");
}

}  // namespace zonesim::clients
