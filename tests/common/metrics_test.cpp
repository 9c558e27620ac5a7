// Metrics JSON lines: what JsonLine writes must parse as JSON with the values given, and
// MetricsWriter must put one object per line in the file.

#include "common/metrics.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace zonesim {
namespace {

using nlohmann::json;

TEST(JsonLine, ParsesWithTheValuesGivenInOrder) {
  JsonLine line;
  line.add("tick", 12)
      .add("rank", std::int64_t{-3})
      .add("ids", std::uint64_t{18446744073709551615ULL})
      .add("dt", 0.25)
      .add("scene", "demo")
      .addRaw("cells", "[1,2,3]");
  json j = json::parse(line.str());
  EXPECT_EQ(j["tick"].get<int>(), 12);
  EXPECT_EQ(j["rank"].get<std::int64_t>(), -3);
  EXPECT_EQ(j["ids"].get<std::uint64_t>(), 18446744073709551615ULL);
  EXPECT_EQ(j["dt"].get<double>(), 0.25);
  EXPECT_EQ(j["scene"].get<std::string>(), "demo");
  EXPECT_EQ(j["cells"], json::parse("[1,2,3]"));
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  EXPECT_EQ(keys.size(), 6u);
  EXPECT_EQ(line.str().find("\"tick\""), 1u);  // written in the order added
}

TEST(JsonLine, EmptyLineIsAnEmptyObject) {
  EXPECT_EQ(json::parse(JsonLine().str()), json::object());
}

TEST(JsonLine, EscapesStringsAndKeys) {
  const std::string nasty =
      "quote\" back\\slash\nnew\ttab\x01"
      "ctl\rcr é";
  JsonLine line;
  line.add("k\"ey", nasty);
  json j = json::parse(line.str());
  EXPECT_EQ(j["k\"ey"].get<std::string>(), nasty);
  EXPECT_EQ(line.str().find('\n'), std::string::npos);  // one record stays one line
}

TEST(JsonLine, NonFiniteNumbersBecomeNull) {
  JsonLine line;
  line.add("nan", std::nan(""))
      .add("inf", std::numeric_limits<double>::infinity())
      .add("ninf", -std::numeric_limits<double>::infinity());
  json j = json::parse(line.str());
  EXPECT_TRUE(j["nan"].is_null());
  EXPECT_TRUE(j["inf"].is_null());
  EXPECT_TRUE(j["ninf"].is_null());
}

TEST(JsonLine, DoublesReadBackExactly) {
  // Wall-clock seconds since the epoch and tiny errors both need all their digits.
  for (double v : {1712345678.123456, 0.1, 1.0 / 3, -2.5e-12, 6.02214076e23}) {
    JsonLine line;
    line.add("v", v);
    EXPECT_EQ(json::parse(line.str())["v"].get<double>(), v) << line.str();
  }
}

class TempFile {
 public:
  TempFile()
      : path_(std::filesystem::temp_directory_path() /
              ("zonesim_metrics_" + std::to_string(::getpid()) + ".jsonl")) {}
  ~TempFile() { std::filesystem::remove(path_); }
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

std::vector<std::string> readLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

TEST(MetricsWriter, WritesOneJsonObjectPerLine) {
  TempFile file;
  {
    MetricsWriter writer(file.path());
    EXPECT_TRUE(writer.enabled());
    for (int tick = 0; tick < 3; ++tick) writer.write(JsonLine().add("tick", tick).add("ms", 1.5));
    writer.flush();
    EXPECT_EQ(readLines(file.path()).size(), 3u);  // flushed before the writer closes
  }
  std::vector<std::string> lines = readLines(file.path());
  ASSERT_EQ(lines.size(), 3u);
  for (int tick = 0; tick < 3; ++tick) {
    json j = json::parse(lines[tick]);
    EXPECT_EQ(j["tick"].get<int>(), tick);
    EXPECT_EQ(j["ms"].get<double>(), 1.5);
  }
}

TEST(MetricsWriter, TruncatesAndMovesWithTheFile) {
  TempFile file;
  { std::ofstream(file.path()) << "old contents\n"; }
  MetricsWriter first(file.path());
  MetricsWriter second(std::move(first));
  EXPECT_FALSE(first.enabled());
  EXPECT_TRUE(second.enabled());
  second.write(JsonLine().add("a", 1));
  second.flush();
  EXPECT_EQ(readLines(file.path()), std::vector<std::string>{"{\"a\":1}"});
}

TEST(MetricsWriter, WithoutPathDoesNothing) {
  MetricsWriter off;
  EXPECT_FALSE(off.enabled());
  off.write(JsonLine().add("a", 1));
  off.flush();
}

TEST(MetricsWriter, UnopenablePathThrows) {
  EXPECT_THROW(MetricsWriter("/nonexistent-dir/zonesim/metrics.jsonl"), std::runtime_error);
}

}  // namespace
}  // namespace zonesim
