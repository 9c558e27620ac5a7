#pragma once
// Metrics as JSON lines: one object per record (per tick, per report interval), appended to a
// file that tools (deploy/report.py) read back. Values are numbers or strings, flat.

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace zonesim {

/// Builds one flat JSON object; keys are written in the order given.
class JsonLine {
 public:
  JsonLine& add(std::string_view key, double value);
  JsonLine& add(std::string_view key, std::int64_t value);
  JsonLine& add(std::string_view key, std::uint64_t value);
  JsonLine& add(std::string_view key, int value) { return add(key, std::int64_t(value)); }
  JsonLine& add(std::string_view key, std::string_view value);
  /// Adds an already-encoded JSON value (array or object) verbatim.
  JsonLine& addRaw(std::string_view key, std::string_view json);
  std::string str() const { return body_ + "}"; }

 private:
  void key(std::string_view k);
  std::string body_ = "{";
};

/// Appends JSON lines to a file; a writer with no path does nothing (metrics off).
class MetricsWriter {
 public:
  MetricsWriter() = default;
  /// Opens (truncates) path; throws std::runtime_error if it cannot.
  explicit MetricsWriter(const std::string& path);
  ~MetricsWriter();
  MetricsWriter(const MetricsWriter&) = delete;
  MetricsWriter& operator=(const MetricsWriter&) = delete;
  MetricsWriter(MetricsWriter&& o) noexcept;
  MetricsWriter& operator=(MetricsWriter&& o) noexcept;

  bool enabled() const { return file_ != nullptr; }
  void write(const JsonLine& line);
  void flush();

 private:
  std::FILE* file_ = nullptr;
};

/// Escapes a string for inclusion in JSON.
std::string jsonEscape(std::string_view s);

}  // namespace zonesim
