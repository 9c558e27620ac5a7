#pragma once
// Moving AI scenario files (.scen): one shortest-path problem per line with its optimal length.

#include <istream>
#include <string>
#include <vector>

#include "ai/octile.h"

namespace zonesim::ai {

/// One problem of a scenario file.
struct ScenarioProblem {
  int bucket = 0;        ///< difficulty bucket from the file
  std::string map_path;  ///< map named by the file (informational: callers choose the map)
  int map_width = 0;     ///< map width the problem was generated for
  int map_height = 0;    ///< map height the problem was generated for
  Cell start;            ///< start cell
  Cell goal;             ///< goal cell
  double optimal = 0.0;  ///< listed optimal length (rounded in the file)
  /// The listed length's last decimal place: 1e-8 for 8 decimals, 0.01 for the 2 that older
  /// files give (1 with none); the file's own rounding is half of it.
  double optimal_step = 1.0;
  int line = 0;          ///< 1-based line in the file, for error messages
};

/// Whether a path length agrees with the problem's listed optimum: within the file's rounding
/// of it (half its last decimal place), or within lengthsAgree's relative tolerance.
bool agreesWithListed(double length, const ScenarioProblem& p);

/// Parses a scenario; accepts tabs or spaces, `version 1` or `version 1.0`, blank lines and
/// CRLF. Throws ParseError naming `file` and the line.
std::vector<ScenarioProblem> parseScenario(std::istream& in, const std::string& file);
/// Reads a scenario file; throws ParseError (line 0 when it cannot be opened).
std::vector<ScenarioProblem> loadScenario(const std::string& path);

}  // namespace zonesim::ai
