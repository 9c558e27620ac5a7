// A node's summary for the benchmark and the test: its traffic, its drops and rejections, what
// it caught of each player, and a peer's votes and exclusions.
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
  // Voting: what this peer sent and heard, whom it excluded (from which tick, and whether still
  // at the end), whom it let back in (last at which tick), and on whom its checker re-anchored
  // after a probation.
  auto byPlayer = [](const std::map<std::uint32_t, std::uint64_t>& m) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [p, n] : m) out[std::to_string(p)] = n;
    return out;
  };
  std::map<std::uint32_t, std::uint64_t> reanchored;
  for (std::uint32_t p = 0; p < config_.players; ++p)
    if (auto n = checker_.reanchoredOf(p)) reanchored[p] = n;
  j["votes_sent"] = votes_sent_;
  j["votes_in"] = votes_in_;
  j["votes_stale"] = votes_stale_;
  j["votes_against_by_voter"] = byPlayer(votes_against_by_voter_);
  j["excluded_since_tick"] = byPlayer(excluded_since_);
  j["excluded_at_end"] = excluded_;
  j["readmitted_at_tick"] = byPlayer(readmitted_at_);
  j["reanchored"] = byPlayer(reanchored);
  j["states_of_excluded"] = states_of_excluded_;
  j["hits_of_excluded"] = hits_of_excluded_;
  std::string path = config_.out_dir + "/node_" + std::to_string(config_.player) + ".json";
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << j.dump() << '\n';
}

}  // namespace zonesim::topo
