#include "common/log.h"

#include <cstdio>
#include <ctime>
#include <mutex>
#include <stdexcept>

#include "common/timer.h"

namespace zonesim::log {

namespace {
Level g_level = Level::Info;
std::string g_tag = "zonesim";
std::mutex g_mutex;
const char* levelName(Level l) {
  switch (l) {
    case Level::Debug: return "debug";
    case Level::Info: return "info";
    case Level::Warn: return "warn";
    case Level::Error: return "error";
    default: return "off";
  }
}
}  // namespace

void setLevel(Level level) { g_level = level; }
Level level() { return g_level; }
void setTag(const std::string& tag) { g_tag = tag; }

Level parseLevel(const std::string& name) {
  for (Level l : {Level::Debug, Level::Info, Level::Warn, Level::Error, Level::Off})
    if (name == levelName(l)) return l;
  throw std::invalid_argument("unknown log level '" + name + "'");
}

void write(Level lvl, const char* fmt, ...) {
  char msg[1024];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(msg, sizeof msg, fmt, args);
  va_end(args);
  double t = double(wallTimeUs() % 100000000ULL) * 1e-6;
  std::lock_guard<std::mutex> lock(g_mutex);
  std::fprintf(stderr, "[%9.3f %s %s] %s\n", t, g_tag.c_str(), levelName(lvl), msg);
}

}  // namespace zonesim::log
