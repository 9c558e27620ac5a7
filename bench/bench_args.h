#pragma once
// Command-line helpers shared by the benchmarks.

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace zonesim::bench {

/// Calls f(item) for each comma-separated item of `text` (empty items included).
template <class F>
void forEachItem(const char* text, F&& f) {
  const std::string s(text);
  std::size_t at = 0;
  while (true) {
    const std::size_t comma = s.find(',', at);
    f(s.substr(at, comma == std::string::npos ? std::string::npos : comma - at));
    if (comma == std::string::npos) return;
    at = comma + 1;
  }
}

/// "1000,10000" as {1000, 10000}. Exits with a message naming the option and the bad item when
/// an item is not a positive whole number (a benchmark with a typo should not run for minutes
/// on a wrong list).
inline std::vector<int> parseCounts(const char* option, const char* text) {
  std::vector<int> out;
  forEachItem(text, [&](const std::string& item) {
    char* end = nullptr;
    const long v = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || v <= 0 || v > 1000000000) {
      std::fprintf(stderr, "%s: '%s' is not a positive whole number (in '%s')\n", option,
                   item.c_str(), text);
      std::exit(2);
    }
    out.push_back(int(v));
  });
  return out;
}

/// "0,0.3" as {0, 0.3}. Exits with a message naming the option and the bad item when an item
/// is not a finite number of at least 0.
inline std::vector<double> parseReals(const char* option, const char* text) {
  std::vector<double> out;
  forEachItem(text, [&](const std::string& item) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !(v >= 0) || v > 1e9) {
      std::fprintf(stderr, "%s: '%s' is not a number of at least 0 (in '%s')\n", option,
                   item.c_str(), text);
      std::exit(2);
    }
    out.push_back(v);
  });
  return out;
}

}  // namespace zonesim::bench
