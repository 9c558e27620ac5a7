#pragma once
// One personalised all-to-all of byte buffers: sizes first (MPI_Alltoall), then the payloads
// (MPI_Alltoallv). Migration and the halo both move their data this way; the buffers are kept
// across ticks so a warmed-up exchange does not allocate. Each received segment starts at a
// multiple of kSegmentAlign, so a FlatBuffer in it can be read in place.

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace zonesim::zone {

class ByteExchange {
 public:
  /// Alignment of every received segment (the widest FlatBuffers scalar, a double).
  static constexpr std::size_t kSegmentAlign = alignof(double);

  ByteExchange(MPI_Comm comm, int size);

  /// Clears the outgoing buffers; call before packing a new round.
  void begin();
  /// The outgoing bytes for rank r (append to it).
  std::vector<std::uint8_t>& outgoing(int r) { return out_[std::size_t(r)]; }
  /// Sends every outgoing buffer to its rank and receives theirs (collective).
  void exchange();
  /// What rank r sent us in the last exchange.
  std::span<const std::uint8_t> received(int r) const;
  /// out[r] to each rank r, and what each rank sent this one, by rank (collective): begin,
  /// outgoing and exchange in one call, for callers that hold their buffers themselves.
  std::vector<std::vector<std::uint8_t>> swap(const std::vector<std::vector<std::uint8_t>>& out);
  /// Bytes this rank sent in the last exchange.
  std::uint64_t bytesSent() const { return bytes_sent_; }

 private:
  MPI_Comm comm_;
  int size_;
  std::vector<std::vector<std::uint8_t>> out_;
  std::vector<int> send_counts_, recv_counts_, send_displs_, recv_displs_;
  std::vector<std::uint8_t> send_buf_, recv_buf_;
  std::uint64_t bytes_sent_ = 0;
};

}  // namespace zonesim::zone
