#include "auth/auth_key.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace zonesim::auth {

AuthKey::AuthKey(std::vector<std::uint8_t> bytes, const std::string& what)
    : bytes_(std::move(bytes)) {
  if (bytes_.size() < kMinKeyBytes)
    throw std::invalid_argument(what + ": " + std::to_string(bytes_.size()) +
                                " bytes, a key needs at least " + std::to_string(kMinKeyBytes) +
                                " (make one with: head -c 32 /dev/urandom > FILE)");
  if (bytes_.size() > kMaxKeyBytes)
    throw std::invalid_argument(what + ": " + std::to_string(bytes_.size()) +
                                " bytes, a key has at most " + std::to_string(kMaxKeyBytes) +
                                ": is this the right file?");
}

AuthKey loadAuthKey(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f)
    throw std::runtime_error("cannot read auth key file " + path + ": " + std::strerror(errno));
  // One byte past the limit is enough to tell a key from a wrong file.
  std::vector<std::uint8_t> bytes;
  char c;
  while (bytes.size() <= kMaxKeyBytes && f.get(c)) bytes.push_back(std::uint8_t(c));
  if (f.bad()) throw std::runtime_error("cannot read auth key file " + path + ": read error");
  try {
    return AuthKey(std::move(bytes), "auth key file " + path);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
}

}  // namespace zonesim::auth
