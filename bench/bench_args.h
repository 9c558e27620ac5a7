#pragma once
// Command-line helpers shared by the benchmarks.

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace zonesim::bench {

/// "1000,10000" as {1000, 10000}. Exits with a message naming the option and the bad item when
/// an item is not a positive whole number (a benchmark with a typo should not run for minutes
/// on a wrong list).
inline std::vector<int> parseCounts(const char* option, const char* text) {
  std::vector<int> out;
  std::string s(text);
  std::size_t at = 0;
  while (at <= s.size()) {
    const std::size_t comma = s.find(',', at);
    const std::string item =
        s.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    char* end = nullptr;
    const long v = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || v <= 0 || v > 1000000000) {
      std::fprintf(stderr, "%s: '%s' is not a positive whole number (in '%s')\n", option,
                   item.c_str(), text);
      std::exit(2);
    }
    out.push_back(int(v));
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  return out;
}

}  // namespace zonesim::bench
