// A node's summary for the benchmark and the test: its traffic, its drops and rejections, and
// what it caught of each player.
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "topologies/topology_node.h"

namespace zonesim::topo {

void TopologyNode::writeSummary(double played_s) const {
  nlohmann::json j;
  j["player"] = config_.player;
  j["role"] = roleName(config_.role);
  j["cheat"] = config_.cheats.names();
  j["cross_check"] = config_.cross_check;
  j["played_s"] = played_s;
  j["bytes_in"] = bytes_in_;
  j["bytes_out"] = bytes_out_;
  j["datagrams_in"] = datagrams_in_;
  j["datagrams_out"] = datagrams_out_;
  j["bytes_in_per_s"] = double(bytes_in_) / played_s;
  j["bytes_out_per_s"] = double(bytes_out_) / played_s;
  j["hits_claimed"] = hits_claimed_;
  j["hits_accepted"] = hits_accepted_;
  j["hits_unjudged"] = hits_unjudged_;
  nlohmann::json drops = nlohmann::json::object(), violations = nlohmann::json::object(),
                 detected = nlohmann::json::object();
  for (std::size_t r = 0; r < std::size_t(gateway::DropReason::Count); ++r)
    if (auto n = drops_[gateway::DropReason(r)])
      drops[gateway::dropReasonName(gateway::DropReason(r))] = n;
  for (std::size_t v = 1; v < std::size_t(Violation::Count); ++v)
    if (auto n = checker_.counts()[v]) violations[violationName(Violation(v))] = n;
  // What this node caught of each player: its drops of their datagrams and its rejections.
  for (std::uint32_t p = 0; p < config_.players; ++p) {
    auto it = drops_by_player_.find(p);
    std::uint64_t n = checker_.rejectedOf(p) + (it == drops_by_player_.end() ? 0 : it->second);
    if (n) detected[std::to_string(p)] = n;
  }
  j["drops"] = drops;
  j["violations"] = violations;
  j["detected_by_player"] = detected;
  std::string path = config_.out_dir + "/node_" + std::to_string(config_.player) + ".json";
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << j.dump() << '\n';
}

}  // namespace zonesim::topo
