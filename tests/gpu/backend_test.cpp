// --gpu on|off|auto: parsing and the auto threshold.

#include "gpu/backend.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace zonesim::gpu {
namespace {

TEST(GpuMode, ParsesTheThreeModes) {
  EXPECT_EQ(parseGpuMode("on"), GpuMode::On);
  EXPECT_EQ(parseGpuMode("off"), GpuMode::Off);
  EXPECT_EQ(parseGpuMode("auto"), GpuMode::Auto);
}

TEST(GpuMode, RejectsAnythingElseNamingTheValue) {
  try {
    parseGpuMode("yes");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'yes'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("on, off or auto"), std::string::npos) << e.what();
  }
}

TEST(ChooseBackend, OnAndOffIgnoreTheCount) {
  EXPECT_EQ(chooseBackend(GpuMode::On, 1, true), Backend::OpenCl);
  EXPECT_EQ(chooseBackend(GpuMode::On, 1, false), Backend::OpenCl);
  EXPECT_EQ(chooseBackend(GpuMode::Off, 100'000'000, true), Backend::Cpu);
}

TEST(ChooseBackend, AutoUsesTheThresholdAndNeedsADevice) {
  EXPECT_EQ(chooseBackend(GpuMode::Auto, kAutoGpuThreshold - 1, true), Backend::Cpu);
  EXPECT_EQ(chooseBackend(GpuMode::Auto, kAutoGpuThreshold, true), Backend::OpenCl);
  EXPECT_EQ(chooseBackend(GpuMode::Auto, 100'000'000, false), Backend::Cpu);
}

TEST(SelectBackend, MatchesChooseBackendWithTheProbedDevice) {
  EXPECT_EQ(selectBackend("off", 100'000'000), Backend::Cpu);
  EXPECT_EQ(selectBackend("on", 0), Backend::OpenCl);
  EXPECT_EQ(selectBackend("auto", 0), Backend::Cpu);
  EXPECT_EQ(selectBackend("auto", kAutoGpuThreshold),
            openClAvailable() ? Backend::OpenCl : Backend::Cpu);
  EXPECT_THROW(selectBackend("gpu", 0), std::invalid_argument);
}

TEST(BackendName, NamesBoth) {
  EXPECT_STREQ(backendName(Backend::Cpu), "cpu");
  EXPECT_STREQ(backendName(Backend::OpenCl), "opencl");
}

}  // namespace
}  // namespace zonesim::gpu
