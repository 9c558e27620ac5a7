#include "topologies/discovery_message.h"

#include <arpa/inet.h>

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace zonesim::topo {

namespace {

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

[[noreturn]] void bad(const std::string& what) {
  throw std::invalid_argument(what);
}

std::uint64_t number(std::string_view text, const char* field, std::uint64_t max) {
  std::uint64_t v = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v > max)
    bad(std::string(field) + " '" + std::string(text) + "' is not a whole number in 0.." +
        std::to_string(max));
  return v;
}

double seconds(std::string_view text, const char* field) {
  std::string s(text);
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
    bad(std::string(field) + " '" + s + "' is not a number of seconds");
  return v;
}

Registration registration(std::string_view player, std::string_view role, std::string_view addr) {
  Registration r;
  r.player = std::uint32_t(number(player, "player", 0xffffffffu));
  r.role = parseRole(role);
  r.address = parseDottedEndpoint(addr);
  return r;
}

}  // namespace

gateway::Endpoint parseDottedEndpoint(std::string_view text) {
  std::size_t colon = text.rfind(':');
  if (colon == std::string_view::npos) bad("address '" + std::string(text) + "' has no ':PORT'");
  std::string host(text.substr(0, colon));
  in_addr a{};
  if (inet_pton(AF_INET, host.c_str(), &a) != 1)
    bad("address '" + std::string(text) + "': '" + host + "' is not a dotted IPv4 address");
  std::uint64_t port = number(text.substr(colon + 1), "port", 65535);
  if (port == 0) bad("address '" + std::string(text) + "': port 0 cannot be sent to");
  return gateway::Endpoint{ntohl(a.s_addr), std::uint16_t(port)};
}

DiscoveryRequest parseRequest(std::string_view text) {
  if (text.size() > kMaxDiscoveryBytes)
    bad("request longer than " + std::to_string(kMaxDiscoveryBytes) + " bytes");
  std::vector<std::string_view> w = words(text);
  if (w.empty()) bad("empty request (expected 'register' or 'list')");
  if (w[0] == "list") {
    if (w.size() != 1) bad("'list' takes no arguments");
    return ListRequest{};
  }
  if (w[0] == "register") {
    if (w.size() != 5)
      bad("'register' takes PLAYER ROLE A.B.C.D:PORT TTL_S, got " + std::to_string(w.size() - 1) +
          " arguments");
    RegisterRequest r{registration(w[1], w[2], w[3]), seconds(w[4], "ttl")};
    if (r.ttl_s <= 0 || r.ttl_s > kMaxTtlSeconds)
      bad("ttl '" + std::string(w[4]) + "' is not in (0, " + std::to_string(int(kMaxTtlSeconds)) +
          "] s");
    return r;
  }
  std::string head(w[0].substr(0, 32));
  bad("unknown request '" + head + "' (expected 'register' or 'list')");
}

std::string formatRequest(const DiscoveryRequest& request) {
  if (std::holds_alternative<ListRequest>(request)) return "list";
  const RegisterRequest& r = std::get<RegisterRequest>(request);
  std::ostringstream s;
  s << "register " << r.registration.player << ' ' << roleName(r.registration.role) << ' '
    << r.registration.address.str() << ' ' << r.ttl_s;
  return s.str();
}

std::string formatPeers(const std::vector<Registration>& entries) {
  std::ostringstream s;
  s << "peers " << entries.size();
  for (const Registration& r : entries)
    s << '\n' << r.player << ' ' << roleName(r.role) << ' ' << r.address.str();
  return s.str();
}

std::vector<Registration> parsePeers(std::string_view text) {
  std::size_t nl = text.find('\n');
  std::vector<std::string_view> head = words(text.substr(0, nl));
  if (!head.empty() && head[0] == "error")
    bad("discovery service refused: " +
        std::string(text.substr(std::min(text.size(), std::size_t(6)))));
  if (head.size() != 2 || head[0] != "peers") bad("reply does not start with 'peers N'");
  std::uint64_t n = number(head[1], "peer count", kMaxDiscoveryBytes);
  std::vector<Registration> out;
  while (nl != std::string_view::npos) {
    std::size_t next = text.find('\n', nl + 1);
    std::vector<std::string_view> w = words(text.substr(
        nl + 1, next == std::string_view::npos ? std::string_view::npos : next - nl - 1));
    if (w.size() != 3)
      bad("peer line " + std::to_string(out.size() + 1) + " is not PLAYER ROLE ADDR:PORT");
    out.push_back(registration(w[0], w[1], w[2]));
    nl = next;
  }
  if (out.size() != n)
    bad("reply says " + std::to_string(n) + " peers but lists " + std::to_string(out.size()));
  return out;
}

}  // namespace zonesim::topo
