#pragma once
// Answers players' leaderboard queries (LeaderboardQuery, through their gateway) from the
// ledger's leaderboard (ledger/leaderboard_cache.h): the newest reading, at most a second old,
// never a wait for the database in the tick. A query that comes before the first reading waits
// for it; a zone without a ledger answers with that reason.

#include <cstdint>
#include <memory>
#include <vector>

#include "ledger/leaderboard_cache.h"

namespace zonesim::zone {

class GatewayLink;
struct LeaderboardRequestMsg;

class LeaderboardService {
 public:
  /// cache: null for a zone without a ledger.
  explicit LeaderboardService(std::unique_ptr<ledger::LeaderboardCache> cache);
  ~LeaderboardService();

  /// Takes the gateways' queries and answers those it can.
  void serve(GatewayLink& link);
  std::uint64_t answered() const { return answered_; }

 private:
  std::unique_ptr<ledger::LeaderboardCache> cache_;
  std::vector<LeaderboardRequestMsg> waiting_;
  std::uint64_t answered_ = 0;
};

}  // namespace zonesim::zone
