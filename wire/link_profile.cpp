#include "wire/link_profile.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "wire/wire_verify.h"

namespace zonesim::gateway {

namespace {

// The presets. Each is one direction; a client applies its profile to its uplink and its
// downlink, so the round trip is about twice delay_ms. Sources (docs/network.md has the table):
// - lan: switched Ethernet, round trips of 0.1-0.5 ms and no loss outside faults.
// - wifi: a home 802.11 network; median latencies of a few ms with a heavy tail from contention
//   and retries, about 1 % residual loss in short bursts (Sui et al., "Characterizing and
//   Improving WiFi Latency in Large-Scale Operational Networks", MobiSys 2016).
// - 4g: LTE round trips of about 50 ms median with ~10 ms of jitter (Huang et al., "An In-depth
//   Study of LTE", SIGCOMM 2013; 3GPP TS 23.203 QCI 3, real-time gaming: 50 ms delay budget and
//   1e-3 packet loss), loss in bursts of a few datagrams around handovers.
// - congested: a broadband link under a bulk transfer, with a bloated drop-tail buffer: the
//   queue adds a heavy tail of delay, loss comes in bursts (Gettys and Nichols, "Bufferbloat:
//   Dark Buffers in the Internet", ACM Queue 2011; ITU-T G.1050's unmanaged-network profiles);
//   errors at ITU-T Y.1541's packet error bound (1e-4), some reordering and duplication.
// - satellite: a geostationary hop, 600 ms round trip (ITU-T G.114 counts ~280 ms one way for
//   a GEO hop; RFC 2488 gives ~560 ms of propagation alone), long loss bursts from rain fade.
std::vector<LinkProfile> makePresets() {
  std::vector<LinkProfile> v;
  LinkProfile lan;
  lan.name = "lan";
  lan.delay_ms = 0.25;
  lan.jitter = JitterShape::Normal;
  lan.jitter_ms = 0.05;
  v.push_back(lan);

  LinkProfile wifi;
  wifi.name = "wifi";
  wifi.delay_ms = 2;
  wifi.jitter = JitterShape::Pareto;
  wifi.jitter_ms = 3;
  wifi.pareto_shape = 2.5;
  wifi.ge_p = 0.005;  // loss 0.005 / 0.505 = 1 %, bursts of 2
  wifi.ge_r = 0.5;
  wifi.rate_kbps = 20000;
  wifi.queue_bytes = 64000;
  v.push_back(wifi);

  LinkProfile lte;
  lte.name = "4g";
  lte.delay_ms = 25;
  lte.jitter = JitterShape::Normal;
  lte.jitter_ms = 5;
  lte.ge_p = 0.0004;  // loss 0.0004 / 0.3337 = 0.12 %, bursts of 3
  lte.ge_r = 1.0 / 3;
  lte.rate_kbps = 10000;
  lte.queue_bytes = 150000;
  v.push_back(lte);

  LinkProfile congested;
  congested.name = "congested";
  congested.delay_ms = 40;
  congested.jitter = JitterShape::Pareto;
  congested.jitter_ms = 25;
  congested.pareto_shape = 2;
  congested.ge_p = 0.01;  // loss 0.01 / 0.26 = 3.8 %, bursts of 4
  congested.ge_r = 0.25;
  congested.reorder = 0.005;
  congested.reorder_gap_ms = 20;
  congested.duplicate = 0.001;
  congested.corrupt = 1e-4;
  congested.rate_kbps = 256;
  congested.queue_bytes = 16000;  // half a second at 256 kbit/s
  v.push_back(congested);

  LinkProfile sat;
  sat.name = "satellite";
  sat.delay_ms = 300;
  sat.jitter = JitterShape::Normal;
  sat.jitter_ms = 10;
  sat.ge_p = 0.0005;  // loss 0.0005 / 0.1005 = 0.5 %, bursts of 10
  sat.ge_r = 0.1;
  sat.rate_kbps = 2000;
  sat.queue_bytes = 150000;
  v.push_back(sat);
  return v;
}

const std::vector<LinkProfile>& presets() {
  static const std::vector<LinkProfile> p = makePresets();
  return p;
}

[[noreturn]] void fail(const std::string& key, const std::string& why) {
  throw std::invalid_argument(key + ": " + why);
}

void probability(const std::string& key, double v) {
  if (!(v >= 0 && v <= 1)) fail(key, "must be a probability in [0, 1]");
}

void within(const std::string& key, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi))
    fail(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

// The plain numeric keys of a profile file.
struct NumberKey {
  const char* key;
  double LinkProfile::*field;
};
constexpr NumberKey kNumberKeys[] = {
    {"delay_ms", &LinkProfile::delay_ms},
    {"jitter_ms", &LinkProfile::jitter_ms},
    {"pareto_shape", &LinkProfile::pareto_shape},
    {"ge_p", &LinkProfile::ge_p},
    {"ge_r", &LinkProfile::ge_r},
    {"loss_good", &LinkProfile::loss_good},
    {"loss_bad", &LinkProfile::loss_bad},
    {"reorder", &LinkProfile::reorder},
    {"reorder_gap_ms", &LinkProfile::reorder_gap_ms},
    {"duplicate", &LinkProfile::duplicate},
    {"corrupt", &LinkProfile::corrupt},
    {"rate_kbps", &LinkProfile::rate_kbps},
};

double number(const std::string& key, const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    fail(key, "'" + text + "' is not a number");
  }
  if (used != text.size() || !std::isfinite(v)) fail(key, "'" + text + "' is not a number");
  return v;
}

std::string trimmed(std::string_view s) {
  std::size_t b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
  return b == std::string_view::npos ? std::string() : std::string(s.substr(b, e - b + 1));
}

void setKey(LinkProfile& p, const std::string& key, const std::string& value) {
  for (const NumberKey& k : kNumberKeys)
    if (key == k.key) {
      p.*k.field = number(key, value);
      return;
    }
  if (key == "preset") {
    auto base = linkPreset(value);
    if (!base) fail(key, "unknown preset '" + value + "'");
    std::string name = p.name;
    p = *base;
    p.name = name;
  } else if (key == "jitter") {
    if (value == "none")
      p.jitter = JitterShape::None;
    else if (value == "uniform")
      p.jitter = JitterShape::Uniform;
    else if (value == "normal")
      p.jitter = JitterShape::Normal;
    else if (value == "pareto")
      p.jitter = JitterShape::Pareto;
    else
      fail(key, "'" + value + "' is not none, uniform, normal or pareto");
  } else if (key == "keep_order") {
    if (value == "true")
      p.keep_order = true;
    else if (value == "false")
      p.keep_order = false;
    else
      fail(key, "'" + value + "' is not true or false");
  } else if (key == "loss") {
    double v = number(key, value);
    probability(key, v);
    p.loss_good = v;
    p.ge_p = 0;
  } else if (key == "queue_bytes") {
    double v = number(key, value);
    if (v < 0 || v != std::floor(v) || v > 1e9) fail(key, "must be a whole number of bytes");
    p.queue_bytes = std::size_t(v);
  } else {
    fail(key, "unknown key");
  }
}

}  // namespace

bool LinkProfile::active() const {
  return delay_ms > 0 || jitter != JitterShape::None || meanLoss() > 0 || reorder > 0 ||
         duplicate > 0 || corrupt > 0 || rate_kbps > 0;
}

bool LinkProfile::lossOnly() const {
  return delay_ms == 0 && jitter == JitterShape::None && reorder == 0 && duplicate == 0 &&
         corrupt == 0 && rate_kbps == 0;
}

double LinkProfile::meanLoss() const {
  if (ge_p <= 0) return loss_good;
  return (ge_r * loss_good + ge_p * loss_bad) / (ge_p + ge_r);
}

void validateLinkProfile(const LinkProfile& p) {
  within("delay_ms", p.delay_ms, 0, 10000);
  within("jitter_ms", p.jitter_ms, 0, 10000);
  if (p.jitter == JitterShape::None && p.jitter_ms > 0)
    fail("jitter_ms", "needs jitter: uniform, normal or pareto");
  if (p.jitter != JitterShape::None && p.jitter_ms <= 0)
    fail("jitter_ms", "must be > 0 with a jitter shape");
  if (!(p.pareto_shape > 1 && p.pareto_shape <= 100))
    fail("pareto_shape", "must be in (1, 100] (the mean exists only above 1)");
  probability("ge_p", p.ge_p);
  if (!(p.ge_r > 0 && p.ge_r <= 1)) fail("ge_r", "must be in (0, 1] (bursts end)");
  probability("loss_good", p.loss_good);
  probability("loss_bad", p.loss_bad);
  probability("reorder", p.reorder);
  within("reorder_gap_ms", p.reorder_gap_ms, 0, 10000);
  if (p.reorder > 0 && p.reorder_gap_ms <= 0)
    fail("reorder_gap_ms", "must be > 0 for reorder to hold anything back");
  probability("duplicate", p.duplicate);
  probability("corrupt", p.corrupt);
  within("rate_kbps", p.rate_kbps, 0, 1e8);
  if (p.rate_kbps > 0 && p.queue_bytes < kMaxDatagramBytes)
    fail("queue_bytes", "must hold at least one datagram (" + std::to_string(kMaxDatagramBytes) +
                            " bytes) in front of rate_kbps");
  if (p.rate_kbps == 0 && p.queue_bytes > 0) fail("queue_bytes", "needs rate_kbps");
}

const std::vector<std::string>& linkPresetNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const LinkProfile& p : presets()) n.push_back(p.name);
    return n;
  }();
  return names;
}

std::optional<LinkProfile> linkPreset(std::string_view name) {
  for (const LinkProfile& p : presets())
    if (p.name == name) return p;
  return std::nullopt;
}

LinkProfile parseLinkProfile(std::string_view text, const std::string& origin) {
  LinkProfile p;
  p.name = origin;
  std::istringstream in{std::string(text)};
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::string where = origin + ":" + std::to_string(number);
    std::string body = trimmed(line.substr(0, line.find('#')));
    if (body.empty()) continue;
    std::size_t colon = body.find(':');
    if (colon == std::string::npos)
      throw std::invalid_argument(where + ": expected 'key: value', got '" + body + "'");
    try {
      setKey(p, trimmed(body.substr(0, colon)), trimmed(body.substr(colon + 1)));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where + ": " + e.what());
    }
  }
  try {
    validateLinkProfile(p);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(origin + ": " + e.what());
  }
  return p;
}

LinkProfile loadLinkProfile(const std::string& preset_or_path) {
  if (auto p = linkPreset(preset_or_path)) return *p;
  std::ifstream f(preset_or_path);
  if (!f) {
    std::string names;
    for (const std::string& n : linkPresetNames()) names += (names.empty() ? "" : ", ") + n;
    throw std::invalid_argument("'" + preset_or_path + "' is neither a preset (" + names +
                                ") nor a readable profile file");
  }
  std::stringstream text;
  text << f.rdbuf();
  return parseLinkProfile(text.str(), preset_or_path);
}

std::vector<LinkShare> parseLinkMix(const std::string& text) {
  std::vector<LinkShare> mix;
  double total = 0;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t colon = item.rfind(':');
    if (colon == std::string::npos || colon == 0)
      throw std::invalid_argument("'" + item + "' is not PROFILE:SHARE");
    LinkShare s;
    s.profile = loadLinkProfile(trimmed(item.substr(0, colon)));
    std::string share = trimmed(item.substr(colon + 1));
    try {
      s.share = number("share", share);
    } catch (const std::invalid_argument&) {
      throw std::invalid_argument("'" + item + "': share '" + share + "' is not a number");
    }
    if (!(s.share > 0 && s.share <= 1))
      throw std::invalid_argument("'" + item + "': share must be in (0, 1]");
    total += s.share;
    mix.push_back(std::move(s));
  }
  if (mix.empty()) throw std::invalid_argument("empty mix");
  if (std::fabs(total - 1) > 1e-6)
    throw std::invalid_argument("shares sum to " + std::to_string(total) + ", not 1");
  return mix;
}

std::size_t linkShareOf(const std::vector<LinkShare>& mix, std::size_t index, std::size_t count) {
  double at = (double(index) + 0.5) / double(count), upto = 0;
  for (std::size_t i = 0; i < mix.size(); ++i) {
    upto += mix[i].share;
    if (at < upto) return i;
  }
  return mix.size() - 1;
}

}  // namespace zonesim::gateway
