#include "common/metrics.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace zonesim {

std::string jsonEscape(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 2);
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out;
}

void JsonLine::key(std::string_view k) {
  if (body_.size() > 1) body_ += ',';
  body_ += '"';
  body_ += jsonEscape(k);
  body_ += "\":";
}

JsonLine& JsonLine::add(std::string_view k, double value) {
  key(k);
  if (!std::isfinite(value)) {
    body_ += "null";  // JSON has no NaN/inf
  } else {
    // Shortest text that reads back as the same double (%.9g rounded epoch seconds to 10 s).
    char buf[32];
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value);
    body_.append(buf, ec == std::errc() ? end : buf);
  }
  return *this;
}

JsonLine& JsonLine::add(std::string_view k, std::int64_t value) {
  key(k);
  body_ += std::to_string(value);
  return *this;
}

JsonLine& JsonLine::add(std::string_view k, std::uint64_t value) {
  key(k);
  body_ += std::to_string(value);
  return *this;
}

JsonLine& JsonLine::add(std::string_view k, std::string_view value) {
  key(k);
  body_ += '"';
  body_ += jsonEscape(value);
  body_ += '"';
  return *this;
}

JsonLine& JsonLine::addRaw(std::string_view k, std::string_view json) {
  key(k);
  body_ += json;
  return *this;
}

MetricsWriter::MetricsWriter(const std::string& path) : file_(std::fopen(path.c_str(), "w")) {
  if (!file_) throw std::runtime_error("cannot open metrics file " + path + ": " + std::strerror(errno));
}

MetricsWriter::~MetricsWriter() {
  if (file_) std::fclose(file_);
}

MetricsWriter::MetricsWriter(MetricsWriter&& o) noexcept : file_(std::exchange(o.file_, nullptr)) {}

MetricsWriter& MetricsWriter::operator=(MetricsWriter&& o) noexcept {
  if (this != &o) {
    if (file_) std::fclose(file_);
    file_ = std::exchange(o.file_, nullptr);
  }
  return *this;
}

void MetricsWriter::write(const JsonLine& line) {
  if (!file_) return;
  std::string s = line.str();
  s += '\n';
  std::fwrite(s.data(), 1, s.size(), file_);
}

void MetricsWriter::flush() {
  if (file_) std::fflush(file_);
}

}  // namespace zonesim
