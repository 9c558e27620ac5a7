// The .scen parser: every variant of the format the benchmarks ship in, and clear errors.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "ai/parse_error.h"
#include "ai/scenario.h"
#include "tests/ai/test_data.h"

namespace zonesim::ai {
namespace {

std::vector<ScenarioProblem> parse(const std::string& text) {
  std::istringstream in(text);
  return parseScenario(in, "t.scen");
}

int errorLine(const std::string& text) {
  try {
    parse(text);
  } catch (const ParseError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("t.scen:" + std::to_string(e.line()) + ": ", 0), 0u)
        << e.what();
    return e.line();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return -1;
}

// Each optimum keeps the precision it was listed with; a length agrees within its rounding.
TEST(ScenarioParser, ComparesAtTheListedPrecision) {
  auto p = parse(
      "version 1\n0 a.map 8 8 0 0 1 1 1.41\n0 a.map 8 8 0 0 1 1 1.41421356\n"
      "0 a.map 8 8 0 0 3 0 3\n0 a.map 8 8 0 0 2 1 2.41421\n");
  ASSERT_EQ(p.size(), 4u);
  EXPECT_DOUBLE_EQ(p[0].optimal_step, 0.01);
  EXPECT_DOUBLE_EQ(p[1].optimal_step, 1e-8);
  EXPECT_DOUBLE_EQ(p[2].optimal_step, 1.0);
  EXPECT_DOUBLE_EQ(p[3].optimal_step, 1e-5);
  const double diagonal = std::sqrt(2.0);
  EXPECT_TRUE(agreesWithListed(diagonal, p[0]));  // 0.0042 off: within 2 decimals' rounding
  EXPECT_FALSE(agreesWithListed(1.43, p[0]));     // a step and a half off
  EXPECT_TRUE(agreesWithListed(diagonal, p[1]));
  EXPECT_FALSE(agreesWithListed(diagonal + 0.01, p[1]));
  EXPECT_TRUE(agreesWithListed(3.0, p[2]));
  EXPECT_FALSE(agreesWithListed(1.0 + 2 * diagonal, p[3]));  // 3.83, not 2.41
}

TEST(ScenarioParser, ReadsTabSeparatedVersion1) {
  auto p = parse("version 1\n3\tmaps/a.map\t512\t256\t1\t2\t3\t4\t5.82843\n");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].bucket, 3);
  EXPECT_EQ(p[0].map_path, "maps/a.map");
  EXPECT_EQ(p[0].map_width, 512);
  EXPECT_EQ(p[0].map_height, 256);
  EXPECT_EQ(p[0].start, (Cell{1, 2}));
  EXPECT_EQ(p[0].goal, (Cell{3, 4}));
  EXPECT_DOUBLE_EQ(p[0].optimal, 5.82843);
  EXPECT_EQ(p[0].line, 2);
}

TEST(ScenarioParser, AcceptsSpacesVersion10DecimalsAndBlankLines) {
  const std::string text =
      "version 1.0\r\n"
      "0 a.map 10 10 0 0 1 1 1.41\r\n"
      "0  a.map   10 10 0 0 2 1   2.41421356\n"
      "\n"
      "1\t a.map \t10\t10\t0\t0\t0\t0\t0\n"
      "\n\n   \n";
  auto p = parse(text);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_DOUBLE_EQ(p[0].optimal, 1.41);
  EXPECT_DOUBLE_EQ(p[1].optimal, 2.41421356);
  EXPECT_EQ(p[2].line, 5);
}

TEST(ScenarioParser, KeepsAMapPathWithSpaces) {
  auto p = parse("version 1\n0 my maps/a b.map 10 10 0 0 1 1 1.41421\n");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].map_path, "my maps/a b.map");
}

TEST(ScenarioParser, ErrorsNameTheLine) {
  EXPECT_EQ(errorLine(""), 1);
  EXPECT_EQ(errorLine("version 2\n"), 1);
  EXPECT_EQ(errorLine("0 a.map 10 10 0 0 1 1 1\n"), 1);
  EXPECT_EQ(errorLine("version 1\n0 a.map 10 10 0 0 1 1\n"), 2);
  EXPECT_EQ(errorLine("version 1\n0 a.map 10 10 0 0 1 1 1\n0 a.map 10 10 0 x 1 1 1\n"), 3);
  EXPECT_EQ(errorLine("version 1\n0 a.map 10 10 0 0 1 1 1.4x\n"), 2);
  EXPECT_EQ(errorLine("version 1\n0 a.map 10 10 0 0 1 1 -1\n"), 2);
  EXPECT_EQ(errorLine("version 1\n\n0 a.map 10 10 0 0 10 1 1\n"), 3);
  EXPECT_EQ(errorLine("version 1\nb a.map 10 10 0 0 1 1 1\n"), 2);
}

TEST(ScenarioParser, ShippedFilesParse) {
  EXPECT_EQ(loadScenario(test::movingAiPath("random512-10-0.map.scen")).size(), 1670u);
  EXPECT_EQ(loadScenario(test::movingAiPath("8room_000.map.scen")).size(), 1940u);
  EXPECT_EQ(loadScenario(test::movingAiPath("maze512-1-0.map.scen")).size(), 11960u);
}

}  // namespace
}  // namespace zonesim::ai
