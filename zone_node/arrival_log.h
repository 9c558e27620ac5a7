#pragma once
// --arrivals: the tick each flow-field NPC reached its destination (zone_node/systems/
// flow_movement.h), kept by the rank that owned it then and written once at the end of the run,
// gathered to rank 0 in id order, so that runs with other settings or rank counts compare line
// by line (bench/tune.py's crowd arrival-time drift).

#include <mpi.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace zonesim::zone {

/// One NPC's arrival: its id and the tick (counted from the scene's start) whose step took it
/// there.
struct FlowArrival {
  std::uint64_t id = 0;
  std::uint64_t tick = 0;
};

class ArrivalLog {
 public:
  /// Keeps arrivals only when `enabled` (a run without --arrivals pays one branch per tick).
  explicit ArrivalLog(bool enabled) : enabled_(enabled) {}

  /// Notes that the NPCs `ids` arrived in tick `tick`.
  void record(std::uint64_t tick, std::span<const std::uint64_t> ids);
  /// This rank's arrivals so far, in the order recorded.
  const std::vector<FlowArrival>& arrivals() const { return arrivals_; }

  /// Collective: every rank calls it; rank 0 writes `path` as CSV (`id,tick`, one line per
  /// arrival, ascending id). Throws std::runtime_error when the file cannot be written, or when
  /// two ranks report one id (an NPC arrives once).
  void write(MPI_Comm comm, const std::string& path) const;

 private:
  bool enabled_;
  std::vector<FlowArrival> arrivals_;
};

}  // namespace zonesim::zone
