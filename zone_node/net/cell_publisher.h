#pragma once
// The publish phase: per interest cell, one CellUpdateBatch per tick carrying that cell's
// enters, dead-reckoning updates and leaves, and a CellKeyframe every K ticks or when a new
// subscriber appears. A cell nobody subscribes to is not encoded at all.

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "common/interest_grid.h"
#include "idl/dds_entity.h"
#include "idl/topics.h"
#include "zone_node/departure.h"
#include "zone_node/entity_store.h"
#include "zone_node/net/dead_reckoning.h"
#include "zonesim.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

/// What one publish phase did (for the tick metrics).
struct PublishStats {
  std::uint64_t cells_written = 0;
  std::uint64_t enters = 0;
  std::uint64_t updates = 0;
  std::uint64_t leaves = 0;
  std::uint64_t keyframes = 0;
  std::uint64_t suppressed = 0;           ///< dead-reckoning checks that needed no update
  std::uint64_t position_updates = 0;     ///< updates sent for the position threshold
  std::uint64_t orientation_updates = 0;  ///< updates sent for the orientation threshold
  std::uint64_t heartbeats = 0;           ///< updates sent for the heartbeat
  std::uint64_t rest_updates = 0;         ///< updates sent because a moving entity stopped
  std::uint64_t subscribed_cells = 0;
  std::uint64_t write_failures = 0;  ///< writes that timed out (a reader not keeping up)
  /// Entities whose client-facing state (motion estimate, orientation rate) was computed: only
  /// those in subscribed cells; a cell nobody reads costs no state and no encoding.
  std::uint64_t states_computed = 0;
  /// Entities whose motion history was kept this tick: those in a read cell or next to one
  /// (where a reader may see them next tick); farther ones cost no history either.
  std::uint64_t histories_kept = 0;
};

class CellPublisher {
 public:
  /// Dead-reckoning models, thresholds, quantisation and keyframe period come from the scene;
  /// every sample carries the cluster epoch.
  CellPublisher(dds_entity_t participant, const dds::Topics& topics, const InterestGrid& grid,
                int zone, const Scene& scene, std::uint32_t epoch);

  /// Creates the writers of every cell the rectangle touches, so that they are matched before
  /// an entity first enters one (a handoff into a fresh cell must not wait for discovery).
  void cover(double min_x, double min_z, double max_x, double max_z);

  /// Publishes this tick's changes; leavers are the entities migrated away (to_rank >= 0) or
  /// destroyed (to_rank < 0) this tick.
  PublishStats publish(EntityStore& store, std::span<const Departure> leavers, std::uint64_t tick,
                       double sim_time);
  /// The cluster's time dilation factor, carried by every sample from now on (gateways run
  /// their clock at it).
  void setDilation(double factor) { dilation_ = factor; }

 private:
  // Readers matched on a writer, kept by DDS's publication-matched listener (it runs on a DDS
  // thread), so a tick reads two counters per cell instead of asking DDS for each writer's
  // status (about 140 ns a writer: 18 us a tick for 64 cells).
  struct MatchCounts {
    std::atomic<std::uint32_t> now{0}, ever{0};
    std::atomic<std::int64_t>* all_now = nullptr;  // the publisher's sum of `now` over writers
  };
  struct Channel {
    // Declared before the writers, so the writers (and their listeners) go first.
    std::unique_ptr<MatchCounts> updates_matched, keyframes_matched;
    dds::PartitionWriter updates;
    dds::PartitionWriter keyframes;
    std::uint32_t matched = 0;       // readers matched on either writer at the last check
    std::uint32_t matched_ever = 0;  // readers ever matched: a rise means a new reader
    bool subscribed = false;
    bool keyframe_due = false;
    bool all_readers_new = false;  // had no reader last tick: the keyframe is all they know
    std::vector<zonesim_dds_EntityUpdate> enters, updates_out, keyframe;
    std::vector<zonesim_dds_EntityLeave> leaves;
  };

  Channel& channel(int cell);
  void refreshSubscriptions(std::uint64_t tick, PublishStats& stats);
  void markCellsNearReaders();
  void write(int cell, Channel& ch, std::uint64_t tick, double sim_time, PublishStats& stats);

  dds_entity_t participant_;
  dds_entity_t update_topic_, keyframe_topic_;
  const InterestGrid& grid_;
  int zone_;
  DeadReckoner reckoner_;
  int keyframe_every_;
  double dilation_ = 1;
  std::uint32_t epoch_;
  double last_sim_time_ = -1;        // previous publish: the step of the acceleration estimates
  // No cell had a reader at the last publish, so no entity was tracked: the next publish with
  // a reader starts every entity's cell and motion history afresh.
  bool idle_ = false;
  bool any_subscribed_ = false;  // a cell had a reader at the last refresh
  // Readers matched now on all writers, kept by the listeners (declared before the channels,
  // whose writers' listeners update it, so it outlives them): while it is 0 and no cell had a
  // reader at the last refresh, the cells need no refresh.
  std::atomic<std::int64_t> readers_now_{0};
  std::map<int, Channel> channels_;  // ordered by cell id: deterministic write order
  // Per grid cell: read, or one of a read cell's 8 neighbours (an entity moves less than a
  // cell a tick); redone when a cell's readers come or go.
  std::vector<std::uint8_t> near_reader_;
  std::vector<int> entity_cell_;     // per store index, this publish: its cell
  std::vector<Channel*> entity_channel_;  // and that cell's channel
};

}  // namespace zonesim::zone
