// The Moving AI .map parser: shipped maps, format variants and errors with line numbers.

#include <gtest/gtest.h>

#include <sstream>

#include "ai/grid_map.h"
#include "ai/parse_error.h"
#include "tests/ai/test_data.h"

namespace zonesim::ai {
namespace {

GridMap parse(const std::string& text) {
  std::istringstream in(text);
  return parseMovingAiMap(in, "t.map");
}

int errorLine(const std::string& text) {
  try {
    parse(text);
  } catch (const ParseError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("t.map:" + std::to_string(e.line()) + ": ", 0), 0u)
        << e.what();
    return e.line();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return -1;
}

TEST(MapParser, ReadsTerrainAndOrientation) {
  GridMap m = parse("type octile\nheight 2\nwidth 3\nmap\n.@G\nSTW\n");
  EXPECT_EQ(m.width(), 3);
  EXPECT_EQ(m.height(), 2);
  EXPECT_TRUE(m.passable(0, 0));
  EXPECT_FALSE(m.passable(1, 0));
  EXPECT_TRUE(m.passable(2, 0));
  EXPECT_TRUE(m.passable(0, 1));
  EXPECT_FALSE(m.passable(1, 1));
  EXPECT_FALSE(m.passable(2, 1));
  EXPECT_FALSE(m.passable(3, 0)) << "off the map is blocked";
  EXPECT_EQ(m.passableCount(), 3);
}

TEST(MapParser, AcceptsCrlfWidthFirstAndTrailingBlankLines) {
  GridMap m = parse("type octile\r\nwidth 2\r\nheight 1\r\nmap\r\n.@\r\n\r\n\n");
  EXPECT_EQ(m.width(), 2);
  EXPECT_EQ(m.height(), 1);
  EXPECT_TRUE(m.passable(0, 0));
  EXPECT_FALSE(m.passable(1, 0));
}

TEST(MapParser, ErrorsNameTheLine) {
  EXPECT_EQ(errorLine("type hex\nheight 1\nwidth 1\nmap\n.\n"), 1);
  EXPECT_EQ(errorLine("type octile\nheight x\nwidth 1\nmap\n.\n"), 2);
  EXPECT_EQ(errorLine("type octile\nheight 1\ndepth 1\nmap\n.\n"), 3);
  EXPECT_EQ(errorLine("type octile\nheight 2\nwidth 2\nmap\n..\n.\n"), 6);
  EXPECT_EQ(errorLine("type octile\nheight 2\nwidth 2\nmap\n..\n.?\n"), 6);
  EXPECT_EQ(errorLine("type octile\nheight 2\nwidth 2\nmap\n..\n"), 6);
  EXPECT_EQ(errorLine("type octile\nheight 1\nwidth 1\nmap\n.\n@\n"), 6);
  EXPECT_EQ(errorLine("type octile\nheight 1\nwidth 1\n"), 4);
}

TEST(MapParser, MissingFileIsAnError) {
  EXPECT_THROW(loadMovingAiMap(test::movingAiPath("no_such.map")), ParseError);
}

TEST(MapParser, ShippedMapsLoad) {
  for (const char* name : {"random512-10-0.map", "8room_000.map", "maze512-1-0.map"}) {
    GridMap m = loadMovingAiMap(test::movingAiPath(name));
    EXPECT_EQ(m.width(), 512) << name;
    EXPECT_EQ(m.height(), 512) << name;
    EXPECT_GT(m.passableCount(), 512 * 512 / 3) << name;
  }
}

TEST(GridMap, ChangesBumpTheVersionOnlyWhenTheCellChanges) {
  GridMap m(4, 4);
  auto v = m.version();
  m.setPassable(1, 1, true);
  EXPECT_EQ(m.version(), v);
  m.setPassable(1, 1, false);
  EXPECT_EQ(m.version(), v + 1);
  EXPECT_FALSE(m.passable(1, 1));
}

}  // namespace
}  // namespace zonesim::ai
