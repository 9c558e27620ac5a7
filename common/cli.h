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

/// Where a UDP server (gateway, lobby) listens, as typed.
struct ListenOptions {
  std::string bind = "127.0.0.1";  ///< ADDR or ADDR:PORT
  int port = -1;                   ///< -1: not given
  std::string port_file;           ///< empty: do not write the bound port
};

/// Adds --bind, --port and --port-file; `who` names who connects there ("players").
inline void addListenOptions(CLI::App& app, ListenOptions& o, const std::string& who) {
  app.add_option("--bind", o.bind,
                 "UDP address for " + who +
                     ", ADDR or ADDR:PORT: an IPv4 address (0.0.0.0 = every interface), an "
                     "interface name or a host name (default 127.0.0.1)");
  app.add_option("--port", o.port, "UDP port, when --bind gives none (default 0 = ephemeral)")
      ->check(CLI::Range(0, 65535));
  app.add_option("--port-file", o.port_file, "write the bound port to this file");
}

/// Applies the common options (call after parsing).
inline void applyCommonOptions(const CommonOptions& opts, const std::string& tag) {
  log::setLevel(log::parseLevel(opts.log_level));
  log::setTag(tag);
}

}  // namespace zonesim
