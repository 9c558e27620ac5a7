#include "zone_node/cluster/byte_exchange.h"

#include <stdexcept>
#include <string>

namespace zonesim::zone {

namespace {
void mpiCheck(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string(what) + " failed");
}
}  // namespace

ByteExchange::ByteExchange(MPI_Comm comm, int size)
    : comm_(comm),
      size_(size),
      out_(std::size_t(size)),
      send_counts_(std::size_t(size)),
      recv_counts_(std::size_t(size)),
      send_displs_(std::size_t(size)),
      recv_displs_(std::size_t(size)) {}

std::vector<std::vector<std::uint8_t>> ByteExchange::swap(
    const std::vector<std::vector<std::uint8_t>>& out) {
  if (out.size() != std::size_t(size_))
    throw std::invalid_argument("byte swap: " + std::to_string(out.size()) + " buffers for " +
                                std::to_string(size_) + " ranks");
  begin();
  for (int r = 0; r < size_; ++r) out_[std::size_t(r)] = out[std::size_t(r)];
  exchange();
  std::vector<std::vector<std::uint8_t>> in(out.size());
  for (int r = 0; r < size_; ++r) {
    const std::span<const std::uint8_t> got = received(r);
    in[std::size_t(r)].assign(got.begin(), got.end());
  }
  return in;
}

void ByteExchange::begin() {
  for (auto& o : out_) o.clear();
}

void ByteExchange::exchange() {
  send_buf_.clear();
  for (int r = 0; r < size_; ++r) {
    const std::vector<std::uint8_t>& o = out_[std::size_t(r)];
    send_displs_[std::size_t(r)] = int(send_buf_.size());
    send_counts_[std::size_t(r)] = int(o.size());
    send_buf_.insert(send_buf_.end(), o.begin(), o.end());
  }
  bytes_sent_ = send_buf_.size();
  mpiCheck(MPI_Alltoall(send_counts_.data(), 1, MPI_INT, recv_counts_.data(), 1, MPI_INT, comm_),
           "MPI_Alltoall");
  int total = 0;
  for (int r = 0; r < size_; ++r) {
    // The receiver chooses its own displacements: padding here changes nothing on the wire.
    total = int((std::size_t(total) + kSegmentAlign - 1) / kSegmentAlign * kSegmentAlign);
    recv_displs_[std::size_t(r)] = total;
    total += recv_counts_[std::size_t(r)];
  }
  recv_buf_.resize(std::size_t(total));
  mpiCheck(
      MPI_Alltoallv(send_buf_.data(), send_counts_.data(), send_displs_.data(), MPI_BYTE,
                    recv_buf_.data(), recv_counts_.data(), recv_displs_.data(), MPI_BYTE, comm_),
      "MPI_Alltoallv");
}

std::span<const std::uint8_t> ByteExchange::received(int r) const {
  return {recv_buf_.data() + recv_displs_[std::size_t(r)],
          std::size_t(recv_counts_[std::size_t(r)])};
}

}  // namespace zonesim::zone
