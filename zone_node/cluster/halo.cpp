#include "zone_node/cluster/halo.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace zonesim::zone {

namespace {

// One ghost on the wire: raw doubles, so a ghost is bitwise the owner's state (the systems'
// results must not depend on which rank a neighbour lives on). Ranks of one job share the
// byte order and double format; the entity records that migrate use FlatBuffers instead.
struct GhostWire {
  std::uint64_t id;
  std::uint64_t kind;             // EntityKind, widened so the record has no padding
  double pos[3], vel[3], rot[4];  // rot: w, x, y, z
  double angular_velocity[3], half_extents[3];
  double radius, half_height, mass, friction, restitution, rolling_resistance;
  std::uint64_t shape_and_sleep;  // shape | sleeping << 8
  // followed by one std::int64_t per registered ghost column (GhostStore::columns)
};
static_assert(sizeof(GhostWire) == 8 * 25, "GhostWire must be packed doubles");

GhostWire pack(const EntityStore& s, std::size_t i) {
  GhostWire w{};
  w.id = s.id[i].value;
  w.kind = std::uint64_t(s.kind[i]);
  for (int k = 0; k < 3; ++k) {
    w.pos[k] = s.pos[i][k];
    w.vel[k] = s.vel[i][k];
  }
  const Quat& q = s.rot[i];
  w.rot[0] = q.w();
  w.rot[1] = q.x();
  w.rot[2] = q.y();
  w.rot[3] = q.z();
  if (s.kind[i] == EntityKind::RigidBody) {
    const BodyData& b = s.body[i];
    for (int k = 0; k < 3; ++k) {
      w.angular_velocity[k] = b.angular_velocity[k];
      w.half_extents[k] = b.half_extents[k];
    }
    w.radius = b.radius;
    w.half_height = b.half_height;
    w.mass = b.mass;
    w.friction = b.friction;
    w.restitution = b.restitution;
    w.rolling_resistance = b.rolling_resistance;
    w.shape_and_sleep = std::uint64_t(b.shape) | (std::uint64_t(b.sleeping) << 8);
  }
  return w;
}

}  // namespace

HaloExchange::HaloExchange(MPI_Comm comm, int rank, int size, double width, double skin)
    : rank_(rank), size_(size), width_(width), skin_(skin), bytes_(comm, size), send_(size) {
  if (!(width >= 0) || !(skin >= 0))
    throw std::invalid_argument("halo width and skin must be >= 0");
}

bool HaloExchange::listsStale(const EntityStore& store, std::uint64_t layout_version) const {
  if (!built_ || layout_version != built_layout_) return true;
  if (store.id != built_ids_) return true;  // same entities at the same indices
  const double limit2 = 0.25 * skin_ * skin_;
  for (std::size_t i = 0; i < store.size(); ++i)
    if ((store.pos[i] - built_pos_[i]).squaredNorm() > limit2) return true;
  return false;
}

void HaloExchange::borders(const EntityStore& store, const ZoneLayout& layout) {
  for (auto& list : send_) list.clear();
  // Only ranks whose zone comes within reach of ours can need anything from us.
  ZoneRect mine = layout.rect(rank_);
  const double reach = width_ + skin_;
  std::vector<int> near;
  std::vector<ZoneRect> rects;
  for (int r = 0; r < size_; ++r) {
    if (r == rank_) continue;
    ZoneRect o = layout.rect(r);
    bool overlaps = o.min_x <= mine.max_x + reach && o.max_x >= mine.min_x - reach &&
                    o.min_z <= mine.max_z + reach && o.max_z >= mine.min_z - reach;
    if (!overlaps) continue;
    near.push_back(r);
    rects.push_back(o);
  }
  built_ids_ = store.id;
  built_pos_.assign(store.pos.begin(), store.pos.end());
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] == EntityKind::Emitter) continue;  // its particles are zone-local effects
    for (std::size_t n = 0; n < near.size(); ++n)
      if (rects[n].distanceTo(store.pos[i].x(), store.pos[i].z()) < reach)
        send_[std::size_t(near[n])].push_back(store.id[i]);
  }
  built_ = true;
}

HaloStats HaloExchange::refresh(const EntityStore& store, const ZoneLayout& layout,
                                std::uint64_t layout_version) {
  HaloStats stats;
  if (size_ == 1) return stats;
  if (listsStale(store, layout_version)) {
    borders(store, layout);
    built_layout_ = layout_version;
    stats.rebuilt = true;
  }
  const std::vector<GhostColumn>& columns = ghosts_.columns();
  column_values_.resize(columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c) columns[c].read(store, column_values_[c]);
  const std::size_t record = sizeof(GhostWire) + columns.size() * sizeof(std::int64_t);
  bytes_.begin();
  for (int r = 0; r < size_; ++r) {
    std::vector<std::uint8_t>& out = bytes_.outgoing(r);
    const std::vector<EntityId>& list = send_[std::size_t(r)];
    out.resize(list.size() * record);
    for (std::size_t k = 0; k < list.size(); ++k) {
      std::optional<std::size_t> i = store.indexOf(list[k]);
      if (!i) throw std::logic_error("halo send list names an entity this zone no longer has");
      GhostWire w = pack(store, *i);
      std::uint8_t* at = out.data() + k * record;
      std::memcpy(at, &w, sizeof w);
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const std::int64_t v = column_values_[c][*i];
        std::memcpy(at + sizeof w + c * sizeof v, &v, sizeof v);
      }
    }
    stats.sent += list.size();
  }
  bytes_.exchange();
  stats.bytes_sent = bytes_.bytesSent();

  ghosts_.clear();
  std::vector<std::int64_t> values(columns.size());
  for (int r = 0; r < size_; ++r) {
    std::span<const std::uint8_t> in = bytes_.received(r);
    if (in.size() % record != 0) throw std::runtime_error("halo payload size is odd");
    for (std::size_t off = 0; off < in.size(); off += record) {
      GhostWire w;
      std::memcpy(&w, in.data() + off, sizeof w);
      if (!values.empty())
        std::memcpy(values.data(), in.data() + off + sizeof w,
                    values.size() * sizeof(std::int64_t));
      BodyData b;
      if (EntityKind(w.kind) == EntityKind::RigidBody) {
        b.angular_velocity =
            Vec3(w.angular_velocity[0], w.angular_velocity[1], w.angular_velocity[2]);
        b.half_extents = Vec3(w.half_extents[0], w.half_extents[1], w.half_extents[2]);
        b.radius = w.radius;
        b.half_height = w.half_height;
        b.mass = w.mass;
        b.friction = w.friction;
        b.restitution = w.restitution;
        b.rolling_resistance = w.rolling_resistance;
        b.shape = std::uint8_t(w.shape_and_sleep & 0xff);
        b.sleeping = (w.shape_and_sleep >> 8) & 1;
      }
      ghosts_.add(EntityId{w.id}, EntityKind(w.kind), Vec3(w.pos[0], w.pos[1], w.pos[2]),
                  Vec3(w.vel[0], w.vel[1], w.vel[2]), Quat(w.rot[0], w.rot[1], w.rot[2], w.rot[3]),
                  b, r, values);
    }
  }
  stats.ghosts = ghosts_.size();
  return stats;
}

}  // namespace zonesim::zone
