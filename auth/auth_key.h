#pragma once
// The key the lobby and the gateways of one cluster share to sign and check connect tokens: a
// file of random bytes (make one with `head -c 32 /dev/urandom > FILE`), read once at start.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace zonesim::auth {

/// Fewest key bytes accepted: HMAC-SHA-256's own output length (RFC 2104 section 3); a
/// shorter key is easier to guess than the tag it protects.
inline constexpr std::size_t kMinKeyBytes = 32;
/// Most key bytes accepted: anything larger is a wrong file, not a key.
inline constexpr std::size_t kMaxKeyBytes = 4096;

/// A shared secret of kMinKeyBytes..kMaxKeyBytes bytes.
class AuthKey {
 public:
  /// Takes the bytes; throws std::invalid_argument naming `what` if there are too few or many.
  AuthKey(std::vector<std::uint8_t> bytes, const std::string& what);
  /// The key's bytes.
  std::span<const std::uint8_t> bytes() const { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

/// Reads a key file; throws std::runtime_error naming the file and what is wrong (missing,
/// unreadable, too short, too long).
AuthKey loadAuthKey(const std::string& path);

}  // namespace zonesim::auth
