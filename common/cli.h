#pragma once
// Command-line options every zonesim program shares, on top of CLI11.
// Include only in main() translation units: CLI11 is header-only and heavy.

#include <CLI/CLI.hpp>

#include <string>

#include "common/log.h"

namespace zonesim {

struct CommonOptions {
  std::string log_level = "info";
};

/// Adds --log-level to the app.
inline void addCommonOptions(CLI::App& app, CommonOptions& opts) {
  app.add_option("--log-level", opts.log_level, "debug, info, warn, error or off")
      ->check(CLI::IsMember({"debug", "info", "warn", "error", "off"}));
}

/// Applies the common options (call after parsing).
inline void applyCommonOptions(const CommonOptions& opts, const std::string& tag) {
  log::setLevel(log::parseLevel(opts.log_level));
  log::setTag(tag);
}

}  // namespace zonesim
