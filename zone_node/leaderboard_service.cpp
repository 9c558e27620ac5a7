#include "zone_node/leaderboard_service.h"

#include <algorithm>

#include "zone_node/net/gateway_link.h"

namespace zonesim::zone {

LeaderboardService::LeaderboardService(std::unique_ptr<ledger::LeaderboardCache> cache)
    : cache_(std::move(cache)) {}

LeaderboardService::~LeaderboardService() = default;

void LeaderboardService::serve(GatewayLink& link) {
  for (LeaderboardRequestMsg& r : link.takeLeaderboardRequests()) waiting_.push_back(r);
  if (waiting_.empty()) return;
  if (!cache_) {
    for (const LeaderboardRequestMsg& r : waiting_)
      link.publishLeaderboard(r.player_id, {}, "no ledger: the zone runs without --ledger");
    answered_ += waiting_.size();
    waiting_.clear();
    return;
  }
  ledger::LeaderboardSnapshot s = cache_->latest();
  if (s.readings == 0) return;  // the first reading is on its way
  for (const LeaderboardRequestMsg& r : waiting_) {
    std::size_t n = std::min<std::size_t>(r.count, s.rows.size());
    link.publishLeaderboard(r.player_id, std::span(s.rows).first(n), s.error);
  }
  answered_ += waiting_.size();
  waiting_.clear();
}

}  // namespace zonesim::zone
