// The address a keyed gateway tells the lobby: the bound one unless given, the bound port
// filling a port left 0, and an error naming the option when only 0.0.0.0 is known.
#include "gateway/load_report.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace zonesim::gateway {
namespace {

TEST(PublicAddress, TheBoundAddressUnlessGiven) {
  Endpoint bound{0x0a4d0003, 7777};
  EXPECT_EQ(publicAddress({0, 0}, bound), bound);
  EXPECT_EQ(publicAddress({0x0a4d0009, 0}, bound), (Endpoint{0x0a4d0009, 7777}));
  EXPECT_EQ(publicAddress({0x0a4d0009, 9000}, bound), (Endpoint{0x0a4d0009, 9000}));
}

TEST(PublicAddress, EveryInterfaceNeedsAnAddress) {
  Endpoint any{0, 7777};
  EXPECT_EQ(publicAddress({0x0a4d0003, 0}, any), (Endpoint{0x0a4d0003, 7777}));
  try {
    publicAddress({0, 0}, any);
    FAIL() << "0.0.0.0 is no address a player can reach";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--public-address"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace zonesim::gateway
