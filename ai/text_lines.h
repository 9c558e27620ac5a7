#pragma once
// Line and token helpers shared by the .map and .scen parsers.

#include <charconv>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

namespace zonesim::ai {

/// Reads one line and drops a trailing '\r' (files written on Windows); false at end of input.
inline bool readLine(std::istream& in, std::string& line) {
  if (!std::getline(in, line)) return false;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

/// Splits on spaces and tabs, dropping empty fields.
inline std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

/// Parses a whole field as an integer; false on any trailing junk.
inline bool parseInt(std::string_view s, int& out) {
  auto res = std::from_chars(s.data(), s.data() + s.size(), out);
  return res.ec == std::errc() && res.ptr == s.data() + s.size();
}

/// Parses a whole field as a finite double; false on any trailing junk.
inline bool parseDouble(std::string_view s, double& out) {
  auto res = std::from_chars(s.data(), s.data() + s.size(), out);
  return res.ec == std::errc() && res.ptr == s.data() + s.size() && out - out == 0.0;
}

}  // namespace zonesim::ai
