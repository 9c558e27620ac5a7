#pragma once
// Minimal leveled logging to stderr with a per-process tag ("zone 2", "gateway").
// printf-style so that call sites stay cheap to compile; messages below the level cost a compare.

#include <cstdarg>
#include <string>

namespace zonesim::log {

enum class Level { Debug = 0, Info = 1, Warn = 2, Error = 3, Off = 4 };

void setLevel(Level level);
Level level();
/// Parses "debug", "info", "warn", "error", "off"; throws std::invalid_argument otherwise.
Level parseLevel(const std::string& name);
void setTag(const std::string& tag);

void write(Level level, const char* fmt, ...) __attribute__((format(printf, 2, 3)));

}  // namespace zonesim::log

#define ZS_LOG(lvl, ...)                                                        \
  do {                                                                          \
    if (int(lvl) >= int(::zonesim::log::level())) ::zonesim::log::write(lvl, __VA_ARGS__); \
  } while (0)
#define ZS_DEBUG(...) ZS_LOG(::zonesim::log::Level::Debug, __VA_ARGS__)
#define ZS_INFO(...) ZS_LOG(::zonesim::log::Level::Info, __VA_ARGS__)
#define ZS_WARN(...) ZS_LOG(::zonesim::log::Level::Warn, __VA_ARGS__)
#define ZS_ERROR(...) ZS_LOG(::zonesim::log::Level::Error, __VA_ARGS__)
