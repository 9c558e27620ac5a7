#include "gateway/downlink_budget.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace zonesim::gateway {

namespace {
std::string number(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}
}  // namespace

void checkBudget(const BudgetSettings& b, std::size_t min_datagram_bytes,
                 const std::string& kbps_name, const std::string& angle_name) {
  if (!std::isfinite(b.kbps) || b.kbps < 0)
    throw std::invalid_argument(kbps_name + ": must be a number >= 0 (0 = no budget), not " +
                                number(b.kbps));
  if (!std::isfinite(b.error_angle_rad) || b.error_angle_rad < 0 ||
      b.error_angle_rad > 85.0 * M_PI / 180.0 + 1e-12)
    throw std::invalid_argument(angle_name + ": must be between 0 and 85 degrees");
  if (!std::isfinite(b.send_bytes) || b.send_bytes <= 0)
    throw std::invalid_argument("--budget-send-bytes: must be a number of bytes > 0, not " +
                                number(b.send_bytes));
  if (!b.enabled()) return;
  double per_second = b.kbps * 1000.0 / 8.0;
  if (per_second < double(min_datagram_bytes)) {
    double least = double(min_datagram_bytes) * 8.0 / 1000.0;
    throw std::invalid_argument(kbps_name + ": " + number(b.kbps) +
                                " kbit/s cannot carry one spawn a second; at least " +
                                std::to_string(int(std::ceil(least))) + " kbit/s");
  }
}

int BudgetSettings::ticksPerSend(double tick_rate) const {
  if (!enabled()) return 1;
  double per_tick = kbps * 1000.0 / 8.0 / (tick_rate + 1);
  int most = std::max(1, int(tick_rate / 3));
  return std::clamp(int(std::ceil(send_bytes / per_tick)), 1, most);
}

ShownError shownError(const CachedEntity& sent, const CachedEntity& newest, double at) {
  dr::WireEntity a = wireEntity(sent), b = wireEntity(newest);
  // The client's clock may run ahead of the newest sample; neither side extrapolates backwards.
  double da = std::max(0.0, at - sent.sim_time), db = std::max(0.0, at - newest.sim_time);
  ShownError e;
  e.position = dr::distance(dr::predictPosition(a.state, a.model.order, da),
                            dr::predictPosition(b.state, b.model.order, db));
  e.orientation = dr::angleBetween(dr::predictRotation(a.state, a.model.spin, da),
                                   dr::predictRotation(b.state, b.model.spin, db));
  return e;
}

void DownlinkBudget::refill(double bytes, double cap_bytes) {
  tokens_ = std::min(tokens_ + bytes, cap_bytes);
}

const CachedEntity* DownlinkBudget::lastSent(std::uint64_t id) const {
  const Tracked* t = entities_.find(id);
  return t != nullptr && t->has_sent ? &t->sent : nullptr;
}

double DownlinkBudget::accumulate(std::uint64_t id, double priority) {
  return entities_.tryEmplace(id, Tracked{}).first->accumulator += priority;
}

void DownlinkBudget::sent(std::uint64_t id, const CachedEntity& e) {
  entities_.insertOrAssign(id, Tracked{e, true, 0.0});
  waiting_next_.erase(id);
}

bool DownlinkBudget::pressed(std::size_t taken, std::size_t waiting, std::size_t waiting_near,
                             double available, double bytes_per_second) {
  if (taken > 0) record_bytes_ = available / double(taken);
  if (waiting_near > 0) return true;
  if (waiting == 0) return false;
  // Before any record went, one that did not fit took at least what was available.
  double per_record = record_bytes_ > 0 ? record_bytes_ : available;
  return double(waiting) * per_record > bytes_per_second * kBacklogSeconds;
}

void DownlinkBudget::adaptRadius(bool pressed, double nimbus, double least, double seconds) {
  double r = std::min(view_radius_, nimbus);
  r *= std::pow(pressed ? kShrinkPerSecond : kGrowPerSecond, std::max(seconds, 0.0));
  view_radius_ = std::clamp(r, std::min(least, nimbus), nimbus);
}

double DownlinkBudget::secondsSinceAdapt(std::int64_t now_ns) {
  double s = last_adapt_ns_ < 0 ? 0.0 : double(now_ns - last_adapt_ns_) * 1e-9;
  last_adapt_ns_ = now_ns;
  return std::clamp(s, 0.0, 1.0);
}

double DownlinkBudget::accumulateSpawn(std::uint64_t id, double priority) {
  const double* was = waiting_.find(id);
  double acc = (was != nullptr ? *was : 0.0) + priority;
  waiting_next_.insertOrAssign(id, acc);
  return acc;
}

void DownlinkBudget::endTick() {
  std::swap(waiting_, waiting_next_);
  waiting_next_.clear();
}

}  // namespace zonesim::gateway
