#include "zone_node/zone_recorder.h"

#include <flatbuffers/flatbuffers.h>

#include "common/interest_grid.h"
#include "common/scene.h"
#include "common/splitmix.h"
#include "recorder/recording_file.h"
#include "recording_generated.h"
#include "zone_node/zone_node.h"

namespace zonesim::zone {

namespace rec = zonesim::recording;

namespace {

constexpr std::uint32_t kHeaderVersion = 1;

rec::Rect rectOf(const ZoneRect& r) {
  return rec::Rect(float(r.min_x), float(r.min_z), float(r.max_x), float(r.max_z));
}

}  // namespace

bool recordedId(std::uint64_t id, std::uint32_t every) {
  return every <= 1 || splitmix64(id) % every == 0;
}

ZoneRecorder::ZoneRecorder(const std::string& dir, const Scene& scene, const ZoneNode& node,
                           std::uint32_t every, bool restarted)
    : writer_(std::make_unique<rec::RecordingWriter>(dir + "/zone_" +
                                                     std::to_string(node.rank()) + ".zsrec")),
      fbb_(std::make_unique<flatbuffers::FlatBufferBuilder>(1 << 16)),
      every_(every == 0 ? 1 : every),
      dt_(scene.dt),
      last_checkpoint_(node.lastCheckpointTick()),
      restart_pending_(restarted) {
  flatbuffers::FlatBufferBuilder& b = *fbb_;
  InterestGrid grid(scene.world, scene.interest_cell_size);
  std::vector<std::string> phases(kPhaseNames.begin(), kPhaseNames.end());
  std::vector<std::string> stages(kStageNames.begin(), kStageNames.end());
  rec::Rect world(float(scene.world.min.x), float(scene.world.min.z), float(scene.world.max.x),
                  float(scene.world.max.z));
  auto header = rec::CreateHeader(
      b, kHeaderVersion, rec::ProcessKind::Zone, node.rank(), b.CreateString(scene.name), &world,
      scene.dt, scene.world.min.x, scene.world.min.z, grid.cell_size(), grid.columns(),
      grid.rows(), b.CreateVectorOfStrings(phases), b.CreateVectorOfStrings(stages), 0, every_,
      node.epoch(), node.tickCount());
  rec::FinishRecordBuffer(b, rec::CreateRecord(b, rec::Frame::Header, header.Union()));
  writer_->write(b, node.tickCount(), /*indexed=*/false);
}

ZoneRecorder::~ZoneRecorder() = default;

void ZoneRecorder::record(const ZoneNode& node, double tick_seconds) {
  const std::uint64_t tick = node.tickCount() - 1;  // the tick just run and published
  const EntityStore& s = node.store();
  const Quarantine& quarantine = node.quarantine();
  const bool any_frozen = quarantine.frozen() > 0;
  entities_.clear();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!recordedId(s.id[i].value, every_)) continue;
    std::uint8_t flags = 0;
    if (s.kind[i] == EntityKind::RigidBody && s.body[i].sleeping)
      flags |= std::uint8_t(rec::EntityFlags::Sleeping);
    if (any_frozen && quarantine.holds(s.id[i])) flags |= std::uint8_t(rec::EntityFlags::Quarantined);
    entities_.emplace_back(s.id[i].value, float(s.pos[i].x()), float(s.pos[i].y()),
                           float(s.pos[i].z()), std::int16_t(node.rank()), std::uint8_t(s.kind[i]),
                           flags);
  }
  const GhostStore& g = node.ghosts();
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (!recordedId(g.id[i].value, every_)) continue;
    entities_.emplace_back(g.id[i].value, float(g.pos[i].x()), float(g.pos[i].y()),
                           float(g.pos[i].z()), std::int16_t(g.owner[i]), std::uint8_t(g.kind[i]),
                           std::uint8_t(rec::EntityFlags::Ghost));
  }

  events_.clear();
  if (restart_pending_) {
    events_.emplace_back(0, node.lastCheckpointTick(), int(node.epoch()), rec::EventKind::Restart);
    restart_pending_ = false;
  }
  for (const Departure& d : node.migratedThisTick())
    events_.emplace_back(d.id.value, 0, d.to_rank, rec::EventKind::Departed);
  for (const Arrival& a : node.arrivedThisTick())
    events_.emplace_back(a.id.value, 0, a.from_rank, rec::EventKind::Arrived);
  for (const CompletedHandoff& h : node.handoffsCompleted()) {
    std::optional<std::size_t> i = s.avatarOf(h.player_id);
    events_.emplace_back(i ? s.id[*i].value : 0, h.ticks, 0, rec::EventKind::FirstInput);
  }
  if (node.counters().rebalances > 0)
    events_.emplace_back(0, node.counters().rebalances, 0, rec::EventKind::Rebalance);
  if (node.lastCheckpointTick() != last_checkpoint_) {
    last_checkpoint_ = node.lastCheckpointTick();
    events_.emplace_back(0, last_checkpoint_, 0, rec::EventKind::Checkpoint);
  }

  const TickProfile& p = node.profile();
  phase_ms_.clear();
  for (double sec : p.seconds) phase_ms_.push_back(float(sec * 1e3));
  stage_ms_.clear();
  for (double sec : p.stage_seconds) stage_ms_.push_back(float(sec * 1e3));

  flatbuffers::FlatBufferBuilder& b = *fbb_;
  b.Clear();
  const rec::Rect rect = rectOf(node.layout().rect(node.rank()));
  auto frame = rec::CreateZoneTick(
      b, tick, double(tick) * dt_, node.epoch(), &rect, b.CreateVectorOfStructs(entities_),
      std::uint32_t(s.size()), b.CreateVectorOfStructs(events_), b.CreateVector(phase_ms_),
      b.CreateVector(stage_ms_), float(tick_seconds * 1e3));
  rec::FinishRecordBuffer(b, rec::CreateRecord(b, rec::Frame::ZoneTick, frame.Union()));
  writer_->write(b, tick);
}

void ZoneRecorder::close() { writer_->close(); }

}  // namespace zonesim::zone
