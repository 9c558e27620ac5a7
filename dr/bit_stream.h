#pragma once
// Bit-level writer and reader for packed entity states: little-endian bit order, values of up
// to 64 bits. The reader never reads past its buffer; an overrun sets a flag and yields zeros,
// so a decoder checks ok() once at the end instead of after every field.

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace zonesim::dr {

class BitWriter {
 public:
  /// Appends the low `bits` bits of v (bits in 0..64).
  void write(std::uint64_t v, int bits) {
    for (int done = 0; done < bits;) {
      if (bit_ % 8 == 0) bytes_.push_back(0);
      int room = 8 - int(bit_ % 8), take = bits - done < room ? bits - done : room;
      std::uint64_t chunk = (v >> done) & ((std::uint64_t{1} << take) - 1);
      bytes_.back() |= std::uint8_t(chunk << (bit_ % 8));
      bit_ += std::size_t(take);
      done += take;
    }
  }
  /// A number of any size: its bit width (7 bits), then the bits.
  void writeVar(std::uint64_t v) {
    int width = v == 0 ? 0 : 64 - __builtin_clzll(v);
    write(std::uint64_t(width), 7);
    write(v, width);
  }
  /// Drops everything after the first `bits` bits (undoes a write that did not fit).
  void truncate(std::size_t bits) {
    bytes_.resize((bits + 7) / 8);
    if (bits % 8 != 0) bytes_.back() &= std::uint8_t((1u << (bits % 8)) - 1);
    bit_ = bits;
  }
  std::size_t bits() const { return bit_; }
  /// Starts an empty stream in `storage`, keeping its capacity (so a writer reused over
  /// buffers that are handed back allocates nothing once they have grown).
  void reset(std::vector<std::uint8_t>&& storage) {
    bytes_ = std::move(storage);
    bytes_.clear();
    bit_ = 0;
  }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
  std::size_t bit_ = 0;
};

class BitReader {
 public:
  explicit BitReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  /// The next `bits` bits (0..64); zero and !ok() once the buffer is exhausted.
  std::uint64_t read(int bits) {
    if (bits < 0 || bits > 64 || bit_ + std::size_t(bits) > bytes_.size() * 8) {
      overrun_ = true;
      bit_ = bytes_.size() * 8;
      return 0;
    }
    std::uint64_t v = 0;
    for (int done = 0; done < bits;) {
      int off = int(bit_ % 8), room = 8 - off, take = bits - done < room ? bits - done : room;
      std::uint64_t chunk = (std::uint64_t(bytes_[bit_ / 8]) >> off) & ((1u << take) - 1);
      v |= chunk << done;
      bit_ += std::size_t(take);
      done += take;
    }
    return v;
  }
  /// A number written by writeVar; a width over 64 is an overrun.
  std::uint64_t readVar() {
    int width = int(read(7));
    if (width > 64) {
      overrun_ = true;
      return 0;
    }
    return read(width);
  }
  bool ok() const { return !overrun_; }
  /// Bits not yet read.
  std::size_t remaining() const { return bytes_.size() * 8 - bit_; }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t bit_ = 0;
  bool overrun_ = false;
};

}  // namespace zonesim::dr
