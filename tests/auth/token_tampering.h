#pragma once
// The forgeries every signed token must refuse, shared by the connect and resume token tests:
// each single flipped bit, one byte short, one byte long, and nothing at all.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace zonesim::auth {

using IsForged = std::function<bool(std::span<const std::uint8_t>)>;

/// "" if forged() holds for every one-bit change of `good`, else the first change it missed.
inline std::string firstFlipAccepted(std::span<const std::uint8_t> good, const IsForged& forged) {
  std::vector<std::uint8_t> b(good.begin(), good.end());
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      b[i] ^= std::uint8_t(1 << bit);
      bool refused = forged(b);
      b[i] ^= std::uint8_t(1 << bit);
      if (!refused) return "byte " + std::to_string(i) + " bit " + std::to_string(bit);
    }
  }
  return "";
}

/// "" if forged() holds for `good` one byte short, one byte long and empty, else which not.
inline std::string firstSizeAccepted(std::span<const std::uint8_t> good, const IsForged& forged) {
  std::vector<std::uint8_t> longer(good.begin(), good.end());
  longer.push_back(0);
  if (!forged(good.first(good.size() - 1))) return "one byte short";
  if (!forged(longer)) return "one byte long";
  if (!forged({})) return "empty";
  return "";
}

}  // namespace zonesim::auth
