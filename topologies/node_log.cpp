#include "topologies/node_log.h"

#include <stdexcept>

namespace zonesim::topo {

namespace {
std::ofstream openCsv(const std::string& path, const char* header) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << header << '\n';
  return f;
}
}  // namespace

NodeLog::NodeLog(const std::string& dir, std::uint32_t player)
    : player_(player),
      views_(
          openCsv(dir + "/views_" + std::to_string(player) + ".csv", "tick,observer,player,x,z")),
      events_(openCsv(dir + "/events_" + std::to_string(player) + ".csv",
                      "event,t_ns,observer,player,vx,vz")) {}

void NodeLog::view(std::uint64_t tick, std::uint32_t player, const dr::V3& pos) {
  views_ << tick << ',' << player_ << ',' << player << ',' << pos.x << ',' << pos.z << '\n';
}

void NodeLog::input(std::int64_t t_ns, const dr::V3& move) {
  events_ << "input," << t_ns << ',' << player_ << ',' << player_ << ',' << move.x << ',' << move.z
          << '\n';
}

void NodeLog::seen(std::int64_t t_ns, std::uint32_t player, const dr::V3& vel) {
  events_ << "seen," << t_ns << ',' << player_ << ',' << player << ',' << vel.x << ',' << vel.z
          << '\n';
}

}  // namespace zonesim::topo
