#include "ai/grid_map.h"

#include <algorithm>
#include <fstream>

#include "ai/parse_error.h"
#include "ai/text_lines.h"

namespace zonesim::ai {

GridMap::GridMap(int width, int height)
    : width_(width), height_(height), cells_(std::size_t(width) * std::size_t(height), 1) {}

void GridMap::setPassable(int x, int y, bool open) {
  std::uint8_t& c = cells_[index(x, y)];
  std::uint8_t v = open ? 1 : 0;
  if (c == v) return;
  c = v;
  ++version_;
}

int GridMap::passableCount() const {
  return int(std::count(cells_.begin(), cells_.end(), std::uint8_t(1)));
}

namespace {

// Header field `name N` with N a positive size; the order of height and width varies in files.
int parseSizeField(std::string_view value, const std::string& file, int lineNo, const char* name) {
  int v = 0;
  if (!parseInt(value, v) || v <= 0 || v > 65536) {
    throw ParseError(file, lineNo, std::string("bad ") + name + " '" + std::string(value) + "'");
  }
  return v;
}

}  // namespace

GridMap parseMovingAiMap(std::istream& in, const std::string& file) {
  std::string line;
  int lineNo = 0;
  int height = -1, width = -1;
  bool sawType = false;
  // Header: `type octile`, `height H`, `width W`, `map` (height and width in either order).
  for (;;) {
    if (!readLine(in, line)) throw ParseError(file, lineNo + 1, "unexpected end of header");
    ++lineNo;
    auto f = splitFields(line);
    if (f.empty()) throw ParseError(file, lineNo, "empty line in header");
    if (f[0] == "map" && f.size() == 1) break;
    if (f.size() != 2) throw ParseError(file, lineNo, "expected `key value`, got '" + line + "'");
    if (f[0] == "type") {
      if (f[1] != "octile") {
        throw ParseError(file, lineNo, "unsupported map type '" + std::string(f[1]) + "'");
      }
      sawType = true;
    } else if (f[0] == "height") {
      height = parseSizeField(f[1], file, lineNo, "height");
    } else if (f[0] == "width") {
      width = parseSizeField(f[1], file, lineNo, "width");
    } else {
      throw ParseError(file, lineNo, "unknown header key '" + std::string(f[0]) + "'");
    }
  }
  if (!sawType) throw ParseError(file, lineNo, "header lacks `type octile`");
  if (height < 0 || width < 0) throw ParseError(file, lineNo, "header lacks height or width");

  GridMap map(width, height);
  for (int y = 0; y < height; ++y) {
    if (!readLine(in, line)) {
      throw ParseError(
          file, lineNo + 1,
          "map ends after " + std::to_string(y) + " of " + std::to_string(height) + " rows");
    }
    ++lineNo;
    if (int(line.size()) != width) {
      throw ParseError(
          file, lineNo,
          "row has " + std::to_string(line.size()) + " cells, expected " + std::to_string(width));
    }
    for (int x = 0; x < width; ++x) {
      char c = line[std::size_t(x)];
      switch (c) {
        case '.':
        case 'G':
        case 'S':
          break;
        case '@':
        case 'O':
        case 'T':
        case 'W':
          map.setPassable(x, y, false);
          break;
        default:
          throw ParseError(
              file, lineNo,
              "unknown terrain '" + std::string(1, c) + "' at column " + std::to_string(x));
      }
    }
  }
  while (readLine(in, line)) {
    ++lineNo;
    if (!splitFields(line).empty()) throw ParseError(file, lineNo, "text after the last row");
  }
  return map;
}

GridMap loadMovingAiMap(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ParseError(path, 0, "cannot open map file");
  return parseMovingAiMap(in, path);
}

}  // namespace zonesim::ai
