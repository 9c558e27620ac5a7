#include "ai/scenario.h"

#include <fstream>

#include "ai/parse_error.h"
#include "ai/text_lines.h"

namespace zonesim::ai {

namespace {

// The seven numeric fields after the map path: width, height, sx, sy, gx, gy, length.
constexpr int kTrailingFields = 7;

// 10^-d for a decimal number written with d digits after its point (1 without one).
double lastDecimalPlace(std::string_view s) {
  std::size_t point = s.find('.');
  if (point == std::string_view::npos) return 1.0;
  std::size_t digits = 0;
  while (point + 1 + digits < s.size() && s[point + 1 + digits] >= '0' &&
         s[point + 1 + digits] <= '9')
    ++digits;
  double step = 1.0;
  for (std::size_t i = 0; i < digits; ++i) step /= 10.0;
  return step;
}

int intField(std::string_view s, const std::string& file, int lineNo, const char* name) {
  int v = 0;
  if (!parseInt(s, v)) {
    throw ParseError(file, lineNo, std::string("bad ") + name + " '" + std::string(s) + "'");
  }
  return v;
}

}  // namespace

std::vector<ScenarioProblem> parseScenario(std::istream& in, const std::string& file) {
  std::vector<ScenarioProblem> out;
  std::string line;
  int lineNo = 0;
  bool sawVersion = false;
  while (readLine(in, line)) {
    ++lineNo;
    auto f = splitFields(line);
    if (f.empty()) continue;
    if (!sawVersion) {
      double v = 0;
      if (f.size() != 2 || f[0] != "version" || !parseDouble(f[1], v) || v != 1.0) {
        throw ParseError(file, lineNo, "expected `version 1` or `version 1.0`, got '" + line + "'");
      }
      sawVersion = true;
      continue;
    }
    // Bucket, map path, then seven numbers; a path with spaces in it keeps the middle fields.
    if (int(f.size()) < 2 + kTrailingFields) {
      throw ParseError(file, lineNo,
                       "expected 9 fields, got " + std::to_string(f.size()) + ": '" + line + "'");
    }
    ScenarioProblem p;
    p.line = lineNo;
    p.bucket = intField(f[0], file, lineNo, "bucket");
    std::size_t pathEnd = f.size() - kTrailingFields;
    const char* pathBegin = f[1].data();
    const char* pathLast = f[pathEnd - 1].data() + f[pathEnd - 1].size();
    p.map_path.assign(pathBegin, pathLast);
    p.map_width = intField(f[pathEnd + 0], file, lineNo, "map width");
    p.map_height = intField(f[pathEnd + 1], file, lineNo, "map height");
    p.start.x = intField(f[pathEnd + 2], file, lineNo, "start x");
    p.start.y = intField(f[pathEnd + 3], file, lineNo, "start y");
    p.goal.x = intField(f[pathEnd + 4], file, lineNo, "goal x");
    p.goal.y = intField(f[pathEnd + 5], file, lineNo, "goal y");
    if (!parseDouble(f[pathEnd + 6], p.optimal) || p.optimal < 0) {
      throw ParseError(file, lineNo, "bad optimal length '" + std::string(f[pathEnd + 6]) + "'");
    }
    p.optimal_step = lastDecimalPlace(f[pathEnd + 6]);
    if (p.map_width <= 0 || p.map_height <= 0) {
      throw ParseError(file, lineNo, "map size must be positive");
    }
    auto onMap = [&](Cell c) {
      return c.x >= 0 && c.y >= 0 && c.x < p.map_width && c.y < p.map_height;
    };
    if (!onMap(p.start) || !onMap(p.goal)) {
      throw ParseError(file, lineNo, "start or goal outside the listed map size");
    }
    out.push_back(std::move(p));
  }
  if (!sawVersion) throw ParseError(file, lineNo + 1, "missing `version` line");
  return out;
}

std::vector<ScenarioProblem> loadScenario(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ParseError(path, 0, "cannot open scenario file");
  return parseScenario(in, path);
}

bool agreesWithListed(double length, const ScenarioProblem& p) {
  // A hair over half a step: the listed value and ours both carry binary rounding.
  return std::fabs(length - p.optimal) <= 0.5 * p.optimal_step * (1.0 + 1e-9) + 1e-12 ||
         lengthsAgree(length, p.optimal);
}

}  // namespace zonesim::ai
