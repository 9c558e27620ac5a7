// The key file: a good one loads; a missing, short or oversized one is an error naming the file
// and what is wrong.
#include "auth/auth_key.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace zonesim::auth {
namespace {

std::string writeKey(const std::string& name, std::size_t bytes) {
  std::string path =
      (std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))).string();
  std::ofstream f(path, std::ios::binary);
  for (std::size_t i = 0; i < bytes; ++i) f.put(char(i * 31 + 1));
  return path;
}

std::string errorOf(const std::string& path) {
  try {
    loadAuthKey(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(AuthKey, LoadsAllBytesOfAGoodFile) {
  std::string path = writeKey("zs_key_good", 48);
  AuthKey k = loadAuthKey(path);
  ASSERT_EQ(k.bytes().size(), 48u);
  EXPECT_EQ(k.bytes()[1], std::uint8_t(32));
  std::filesystem::remove(path);
}

TEST(AuthKey, MissingFileNamesItAndTheCause) {
  std::string e = errorOf("/nonexistent/zs.key");
  EXPECT_NE(e.find("/nonexistent/zs.key"), std::string::npos) << e;
  EXPECT_NE(e.find("No such file"), std::string::npos) << e;
}

TEST(AuthKey, ShortFileIsRefused) {
  std::string path = writeKey("zs_key_short", 31);
  std::string e = errorOf(path);
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("31 bytes"), std::string::npos) << e;
  EXPECT_NE(e.find("at least 32"), std::string::npos) << e;
  std::filesystem::remove(path);
  path = writeKey("zs_key_empty", 0);
  EXPECT_NE(errorOf(path).find("0 bytes"), std::string::npos);
  std::filesystem::remove(path);
}

TEST(AuthKey, OversizedFileIsRefused) {
  std::string path = writeKey("zs_key_big", kMaxKeyBytes + 100);
  std::string e = errorOf(path);
  EXPECT_NE(e.find("at most"), std::string::npos) << e;
  std::filesystem::remove(path);
}

TEST(AuthKey, DirectoryIsAnError) {
  std::string e = errorOf(std::filesystem::temp_directory_path().string());
  EXPECT_FALSE(e.empty());
}

}  // namespace
}  // namespace zonesim::auth
