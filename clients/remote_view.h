#pragma once
// What one simulated player knows of the world: the entities the gateway spawned for it, each
// with its last received state and when it arrived. What the player "sees" is that state moved
// forward by first-order dead reckoning (position + velocity * time since receipt).

#include <cstdint>
#include <optional>
#include <unordered_map>

#include "client_protocol_generated.h"

namespace zonesim::clients {

/// A planar-and-height point.
struct Point3 {
  double x = 0, y = 0, z = 0;
};

class RemoteView {
 public:
  /// Adds (or replaces) an entity from a Spawn.
  void spawn(const proto::EntityState& s, std::int64_t now_ns);
  /// Applies a StateBatch entry; returns the distance between where the entity was predicted to
  /// be and where the update puts it (the correction the player sees), or nullopt if unknown.
  std::optional<double> update(const proto::EntityState& s, std::int64_t now_ns);
  /// Removes an entity; false if it was not known.
  bool despawn(std::uint64_t id);
  /// Dead-reckoned position of an entity at now_ns.
  std::optional<Point3> predicted(std::uint64_t id, std::int64_t now_ns) const;
  std::size_t size() const { return entities_.size(); }

 private:
  struct Remote {
    proto::EntityState state;
    std::int64_t received_ns;
  };
  static Point3 extrapolate(const Remote& r, std::int64_t now_ns);
  std::unordered_map<std::uint64_t, Remote> entities_;
};

}  // namespace zonesim::clients
