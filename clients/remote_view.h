#pragma once
// What one simulated player knows of the world: the entities the gateway spawned for it, each
// with the dead-reckoning state it was last sent (the same model the zone runs, dr/dr_model.h),
// and what the player is shown: that model extrapolated to the estimated server time, with
// corrections either snapped or converged by projective velocity blending.

#include <cstdint>
#include <optional>
#include <unordered_map>

#include "dr/dr_model.h"
#include "dr/state_codec.h"

namespace zonesim::clients {

/// A planar-and-height point.
struct Point3 {
  double x = 0, y = 0, z = 0;
};

/// How corrections reach the screen.
struct Reconstruction {
  bool blend = true;         ///< projective velocity blending; false: snap to the new model
  double blend_s = 0.25;     ///< convergence time of a blend, seconds
  double sim_dt = 1.0 / 30;  ///< simulated seconds per server tick
};

class RemoteView {
 public:
  explicit RemoteView(Reconstruction r = {}) : r_(r) {}
  void configure(const Reconstruction& r) { r_ = r; }

  /// Adds (or replaces) an entity from a Spawn; now is the estimated server tick (fractional).
  void spawn(const dr::WireEntity& e, double now);
  /// Applies an update; returns the distance between where the entity was shown and where the
  /// new model puts it now (the correction), or nullopt if unknown or not newer than what is held.
  std::optional<double> update(const dr::WireEntity& e, double now);
  /// Removes an entity; false if it was not known.
  bool despawn(std::uint64_t id);
  /// Where the entity is shown at server tick `now` (model, blended or snapped).
  std::optional<Point3> shown(std::uint64_t id, double now) const;
  /// Where the latest model alone puts it (no blending).
  std::optional<Point3> predicted(std::uint64_t id, double now) const;
  /// The latest state held (nullptr if unknown).
  const dr::WireEntity* find(std::uint64_t id) const;
  std::size_t size() const { return entities_.size(); }
  /// Visits (id, entity) in unspecified order.
  template <typename F>
  void forEach(F&& f) const {
    for (const auto& [id, r] : entities_) f(id, r.latest);
  }

 private:
  struct Remote {
    dr::WireEntity latest;
    // Blend: from the shown position and velocity at blend_start to the new model.
    dr::V3 from_pos, from_vel;
    double blend_start = 0;
    bool blending = false;
  };
  dr::V3 model(const dr::WireEntity& e, double now) const;
  dr::V3 modelVelocity(const dr::WireEntity& e, double now) const;
  dr::V3 shownPosition(const Remote& r, double now) const;

  Reconstruction r_;
  std::unordered_map<std::uint64_t, Remote> entities_;
};

}  // namespace zonesim::clients
