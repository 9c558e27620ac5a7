// Link profiles (wire/link_profile.h): the presets, the file format, and the one-line errors
// that name the key of anything that cannot be applied.
#include "wire/link_profile.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace zonesim::gateway {
namespace {

// The message parseLinkProfile throws for text, or "" if it parses.
std::string errorOf(const std::string& text) {
  try {
    parseLinkProfile(text, "f.link");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(LinkProfile, PresetsAreValidAndNamed) {
  std::vector<std::string> want{"lan", "wifi", "4g", "congested", "satellite"};
  EXPECT_EQ(linkPresetNames(), want);
  for (const std::string& name : want) {
    auto p = linkPreset(name);
    ASSERT_TRUE(p) << name;
    EXPECT_EQ(p->name, name);
    EXPECT_NO_THROW(validateLinkProfile(*p)) << name;
    EXPECT_TRUE(p->active()) << name;
  }
  EXPECT_FALSE(linkPreset("5g"));
  EXPECT_EQ(linkPreset("lan")->meanLoss(), 0);
  EXPECT_DOUBLE_EQ(2 * linkPreset("satellite")->delay_ms, 600) << "a GEO round trip";
  EXPECT_GT(linkPreset("congested")->meanLoss(), linkPreset("4g")->meanLoss());
}

TEST(LinkProfile, FileKeysOverrideAPresetBase) {
  LinkProfile p = parseLinkProfile(
      "# a slower 4g\npreset: 4g\ndelay_ms: 40   # one way\njitter: pareto\njitter_ms: 8\n"
      "pareto_shape: 3\nkeep_order: false\nqueue_bytes: 20000\nrate_kbps: 500\n",
      "slow.link");
  EXPECT_EQ(p.name, "slow.link");
  EXPECT_EQ(p.delay_ms, 40);
  EXPECT_EQ(p.jitter, JitterShape::Pareto);
  EXPECT_EQ(p.pareto_shape, 3);
  EXPECT_FALSE(p.keep_order);
  EXPECT_EQ(p.queue_bytes, 20000u);
  EXPECT_EQ(p.ge_p, linkPreset("4g")->ge_p) << "what the file does not set stays the preset's";
  LinkProfile bernoulli = parseLinkProfile("loss: 0.1\n", "b");
  EXPECT_DOUBLE_EQ(bernoulli.meanLoss(), 0.1);
}

TEST(LinkProfile, WhatCannotBeAppliedIsRefusedNamingTheKey) {
  EXPECT_EQ(errorOf("delay_ms: 5\n"), "");
  EXPECT_EQ(errorOf("dealy_ms: 5\n"), "f.link:1: dealy_ms: unknown key");
  EXPECT_EQ(errorOf("\ndelay_ms: five\n"), "f.link:2: delay_ms: 'five' is not a number");
  EXPECT_EQ(errorOf("delay_ms 5\n"), "f.link:1: expected 'key: value', got 'delay_ms 5'");
  EXPECT_EQ(errorOf("preset: 5g\n"), "f.link:1: preset: unknown preset '5g'");
  EXPECT_EQ(errorOf("jitter: gamma\n"),
            "f.link:1: jitter: 'gamma' is not none, uniform, normal or pareto");
  EXPECT_EQ(errorOf("keep_order: maybe\n"), "f.link:1: keep_order: 'maybe' is not true or false");
  EXPECT_EQ(errorOf("ge_p: 1.5\n"), "f.link: ge_p: must be a probability in [0, 1]");
  EXPECT_EQ(errorOf("ge_p: 0.1\nge_r: 0\n"), "f.link: ge_r: must be in (0, 1] (bursts end)");
  EXPECT_EQ(errorOf("jitter_ms: 4\n"),
            "f.link: jitter_ms: needs jitter: uniform, normal or pareto");
  EXPECT_EQ(errorOf("jitter: pareto\njitter_ms: 4\npareto_shape: 1\n"),
            "f.link: pareto_shape: must be in (1, 100] (the mean exists only above 1)");
  EXPECT_EQ(errorOf("reorder: 0.1\n"),
            "f.link: reorder_gap_ms: must be > 0 for reorder to hold anything back");
  EXPECT_EQ(errorOf("rate_kbps: 100\nqueue_bytes: 100\n"),
            "f.link: queue_bytes: must hold at least one datagram (1400 bytes) in front of "
            "rate_kbps");
  EXPECT_EQ(errorOf("queue_bytes: 5000\n"), "f.link: queue_bytes: needs rate_kbps");
  EXPECT_EQ(errorOf("queue_bytes: 1.5\n"),
            "f.link:1: queue_bytes: must be a whole number of bytes");
  EXPECT_EQ(errorOf("delay_ms: -1\n").rfind("f.link: delay_ms: must be in [", 0), 0u);
  EXPECT_EQ(errorOf("corrupt: nan\n"), "f.link:1: corrupt: 'nan' is not a number");
}

TEST(LinkProfile, LoadsPresetsThenFiles) {
  EXPECT_EQ(loadLinkProfile("wifi").name, "wifi");
  std::string path = testing::TempDir() + "link_profile_test.link";
  std::ofstream(path) << "preset: lan\nduplicate: 0.5\n";
  LinkProfile p = loadLinkProfile(path);
  EXPECT_EQ(p.duplicate, 0.5);
  EXPECT_EQ(p.delay_ms, linkPreset("lan")->delay_ms);
  std::remove(path.c_str());
  try {
    loadLinkProfile("/no/such.link");
    FAIL() << "a missing file is an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "'/no/such.link' is neither a preset (lan, wifi, 4g, congested, satellite) nor "
                 "a readable profile file");
  }
}

TEST(LinkProfile, MixesShareThePlayersOutByTheirShares) {
  std::vector<LinkShare> mix = parseLinkMix("lan:0.5,4g:0.25,congested:0.25");
  ASSERT_EQ(mix.size(), 3u);
  std::vector<int> count(3);
  for (std::size_t i = 0; i < 32; ++i) ++count[linkShareOf(mix, i, 32)];
  EXPECT_EQ(count, (std::vector<int>{16, 8, 8}));
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(linkShareOf(mix, i, 3), i) << "at 1/6, 3/6, 5/6";
  auto error = [](const std::string& text) {
    try {
      parseLinkMix(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error("lan:0.5,4g:0.6"), "shares sum to 1.100000, not 1");
  EXPECT_EQ(error("lan"), "'lan' is not PROFILE:SHARE");
  EXPECT_EQ(error("lan:half"), "'lan:half': share 'half' is not a number");
  EXPECT_EQ(error("lan:0,4g:1"), "'lan:0': share must be in (0, 1]");
  EXPECT_EQ(error("5g:1").rfind("'5g' is neither a preset", 0), 0u);
}

}  // namespace
}  // namespace zonesim::gateway
