// Addresses as users type them (--bind, --gateway) and the errors a bad one gets; binding an
// address or a port that is not free.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <net/if.h>

#include <array>
#include <stdexcept>
#include <string>

#include "wire/udp_socket.h"

namespace zonesim::gateway {
namespace {

std::uint32_t ipv4(const char* dotted) {
  in_addr a{};
  EXPECT_EQ(inet_pton(AF_INET, dotted, &a), 1);
  return ntohl(a.s_addr);
}

// The message of the std::invalid_argument that f throws ("" if it throws none).
template <class F>
std::string refusal(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ResolveEndpoint, NumericAddressAndPort) {
  Endpoint e = resolveEndpoint("10.77.0.3:4000");
  EXPECT_EQ(e.address, ipv4("10.77.0.3"));
  EXPECT_EQ(e.port, 4000);
  EXPECT_EQ(e.str(), "10.77.0.3:4000");
}

TEST(ResolveEndpoint, LocalhostResolvesToLoopback) {
  Endpoint e = resolveEndpoint("localhost:65535");
  EXPECT_EQ(e.address >> 24, 127u);
  EXPECT_EQ(e.port, 65535);
}

TEST(ResolveEndpoint, RefusalsSayWhatIsWrong) {
  EXPECT_NE(refusal([] { resolveEndpoint("127.0.0.1"); }).find("expected HOST:PORT"),
            std::string::npos);
  EXPECT_NE(refusal([] { resolveEndpoint(":4000"); }).find("no host"), std::string::npos);
  for (const char* bad : {"127.0.0.1:0", "127.0.0.1:65536", "127.0.0.1:4x", "127.0.0.1:",
                          "127.0.0.1:-1", "127.0.0.1:+5"})
    EXPECT_NE(refusal([&] { resolveEndpoint(bad); }).find("bad port"), std::string::npos) << bad;
  // .invalid never resolves (RFC 6761), so this does not depend on the machine's DNS.
  std::string unknown = refusal([] { resolveEndpoint("no-such-host.invalid:4000"); });
  EXPECT_NE(unknown.find("cannot resolve host 'no-such-host.invalid'"), std::string::npos)
      << unknown;
}

TEST(ParseBindAddress, AddressWithOrWithoutPort) {
  Endpoint any = parseBindAddress("0.0.0.0", 4100);
  EXPECT_EQ(any.address, 0u);
  EXPECT_EQ(any.port, 4100);
  Endpoint given = parseBindAddress("127.0.0.2:0", 4100);
  EXPECT_EQ(given.address, ipv4("127.0.0.2"));
  EXPECT_EQ(given.port, 0);  // ephemeral, as typed: the default applies only when none is
  EXPECT_EQ(parseBindAddress("localhost", 0).address >> 24, 127u);
}

TEST(ParseBindAddress, InterfaceNameGivesItsAddress) {
  // The loopback interface's name differs between systems; look it up by index 1, which
  // Linux gives to lo.
  std::array<char, IF_NAMESIZE> name{};
  ASSERT_NE(if_indextoname(1, name.data()), nullptr);
  EXPECT_EQ(parseBindAddress(name.data(), 7).address, ipv4("127.0.0.1"));
}

TEST(ParseBindAddress, RefusalsSayWhatIsWrong) {
  EXPECT_NE(refusal([] { parseBindAddress("127.0.0.1:99999", 0); }).find("bad port '99999'"),
            std::string::npos);
  EXPECT_NE(refusal([] { parseBindAddress(":80", 0); }).find("no address"), std::string::npos);
  EXPECT_NE(refusal([] { parseBindAddress("nowhere.invalid", 0); }).find("cannot resolve"),
            std::string::npos);
}

TEST(UdpSocket, BindsTheGivenAddress) {
  UdpSocket s(parseBindAddress("127.0.0.1:0", 0));
  EXPECT_EQ(s.local().address, ipv4("127.0.0.1"));
  EXPECT_NE(s.localPort(), 0);
  UdpSocket wildcard(Endpoint::any(0));
  EXPECT_EQ(wildcard.local().address, 0u);
}

TEST(UdpSocket, WildcardSocketTalksWithLoopback) {
  // The client side binds every interface; the gateway still sees a loopback source.
  UdpSocket client(Endpoint::any(0)), server(0);
  std::array<std::uint8_t, 3> bytes{1, 2, 3};
  ASSERT_TRUE(client.sendTo(Endpoint::loopback(server.localPort()), bytes));
  std::array<std::uint8_t, 16> buf{};
  std::optional<Received> got;
  for (int i = 0; i < 1000 && !got; ++i) got = server.receive(buf);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->size, 3u);
  EXPECT_EQ(got->from.address >> 24, 127u);
  EXPECT_EQ(got->from.port, client.localPort());
}

TEST(UdpSocket, PortInUseIsABindErrorNamingTheAddress) {
  UdpSocket first(0);
  Endpoint taken = Endpoint::loopback(first.localPort());
  try {
    UdpSocket second(taken);
    FAIL() << "bound a port already in use";
  } catch (const BindError& e) {
    EXPECT_EQ(e.code(), std::errc::address_in_use);
    EXPECT_EQ(e.where(), taken);
    EXPECT_NE(std::string(e.what()).find("cannot bind " + taken.str()), std::string::npos);
  }
}

TEST(UdpSocket, ForeignAddressIsABindError) {
  // 192.0.2.0/24 is TEST-NET-1 (RFC 5737): never assigned to a local interface.
  try {
    UdpSocket s(resolveEndpoint("192.0.2.1:4000"));
    FAIL() << "bound an address that is not local";
  } catch (const BindError& e) {
    EXPECT_EQ(e.code(), std::errc::address_not_available);
  }
}

}  // namespace
}  // namespace zonesim::gateway
