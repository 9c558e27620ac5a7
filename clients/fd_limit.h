#pragma once
// The open-file limit a fleet needs. Every player has its own UDP socket (the gateway keys
// sessions by address and port, and a lobby's connect token names them), so 2,000 players are
// past the usual soft limit of 1,024 descriptors. The soft limit is raised as far as the hard
// limit allows, which needs no privilege; past the hard limit the fleet cannot start.

#include <cstddef>
#include <cstdint>
#include <stdexcept>

namespace zonesim::clients {

/// The hard RLIMIT_NOFILE is below what a fleet needs; what() names both figures.
class FdLimitError : public std::runtime_error {
 public:
  FdLimitError(std::size_t needed, std::uint64_t hard);
  std::size_t needed() const { return needed_; }
  std::uint64_t hard() const { return hard_; }

 private:
  std::size_t needed_;
  std::uint64_t hard_;
};

/// Descriptors a fleet of `players` needs: a socket each, and a few to spare for the standard
/// streams, the epoll set, the output files and a name lookup's socket.
std::size_t fleetDescriptors(std::size_t players);

/// Raises the soft RLIMIT_NOFILE to `needed` if it is lower (never lowers it). Throws
/// FdLimitError if the hard limit is lower, std::system_error if the kernel refuses.
void raiseFdLimit(std::size_t needed);

}  // namespace zonesim::clients
