#pragma once
// SHA-256 (FIPS 180-4), written here so that signing connect tokens needs no new dependency.
// Streaming: update() any number of times, then finish() once.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace zonesim::auth {

/// Bytes in a SHA-256 digest.
inline constexpr std::size_t kSha256Bytes = 32;
/// Bytes in one SHA-256 message block (HMAC pads its key to this).
inline constexpr std::size_t kSha256BlockBytes = 64;

/// A SHA-256 digest.
using Digest = std::array<std::uint8_t, kSha256Bytes>;

/// Incremental SHA-256 over a byte stream.
class Sha256 {
 public:
  /// The initial hash value of FIPS 180-4 section 5.3.3.
  Sha256();
  /// Appends bytes to the message.
  void update(std::span<const std::uint8_t> bytes);
  /// Pads, returns the digest; the object must not be used afterwards.
  Digest finish();

 private:
  void compress(const std::uint8_t* block);

  std::array<std::uint32_t, 8> state_;
  std::array<std::uint8_t, kSha256BlockBytes> block_{};
  std::size_t block_used_ = 0;
  std::uint64_t total_bytes_ = 0;
};

/// The digest of one message.
Digest sha256(std::span<const std::uint8_t> bytes);

}  // namespace zonesim::auth
