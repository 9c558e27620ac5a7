#pragma once
// What a node writes for bench/net/topology_bench.py: its views of every player each sampled
// tick (consistency between players), its input events and the velocity changes it saw of
// others (latency from an input to its effect), and its summary (bandwidth, detections).

#include <cstdint>
#include <fstream>
#include <string>

#include "dr/dr_state.h"

namespace zonesim::topo {

class NodeLog {
 public:
  /// Opens DIR/views_<player>.csv and DIR/events_<player>.csv; throws std::runtime_error
  /// naming the file if it cannot.
  NodeLog(const std::string& dir, std::uint32_t player);
  /// Where this node shows `player` at tick (its own avatar: the truth).
  void view(std::uint64_t tick, std::uint32_t player, const dr::V3& pos);
  /// This node chose a new input at wall time t_ns.
  void input(std::int64_t t_ns, const dr::V3& move);
  /// This node received a state of `player` whose velocity differs from the one it saw before.
  void seen(std::int64_t t_ns, std::uint32_t player, const dr::V3& vel);

 private:
  std::uint32_t player_;
  std::ofstream views_, events_;
};

}  // namespace zonesim::topo
