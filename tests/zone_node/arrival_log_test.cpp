// zone_node --arrivals (zone_node/arrival_log.h) on one rank: arrivals are kept only when
// enabled, written as `id,tick` in id order, and an NPC reported twice is an error naming it.

#include "zone_node/arrival_log.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace zonesim::zone {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ArrivalLog, WritesEveryArrivalInIdOrder) {
  ArrivalLog log(true);
  const std::vector<std::uint64_t> first = {42, 7}, second = {3};
  log.record(10, first);
  log.record(11, {});
  log.record(12, second);
  EXPECT_EQ(log.arrivals().size(), 3u);
  const std::string path = tempPath("zs_arrival_log_test.csv");
  log.write(MPI_COMM_WORLD, path);
  EXPECT_EQ(readAll(path), "id,tick\n3,12\n7,10\n42,10\n");
  std::filesystem::remove(path);
}

TEST(ArrivalLog, KeepsNothingWhenDisabled) {
  ArrivalLog log(false);
  const std::vector<std::uint64_t> ids = {1, 2};
  log.record(5, ids);
  EXPECT_TRUE(log.arrivals().empty());
}

TEST(ArrivalLog, AnNpcArrivingTwiceIsAnError) {
  ArrivalLog log(true);
  const std::vector<std::uint64_t> ids = {9};
  log.record(4, ids);
  log.record(8, ids);
  try {
    log.write(MPI_COMM_WORLD, tempPath("zs_arrival_log_twice.csv"));
    ADD_FAILURE() << "accepted an NPC arriving twice";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("NPC 9 arrived twice (ticks 4 and 8)"), std::string::npos)
        << e.what();
  }
}

TEST(ArrivalLog, AnUnwritablePathIsAnErrorNamingIt) {
  ArrivalLog log(true);
  try {
    log.write(MPI_COMM_WORLD, "/nonexistent-dir/arrivals.csv");
    ADD_FAILURE() << "wrote into a missing folder";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write /nonexistent-dir/arrivals.csv"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace zonesim::zone
