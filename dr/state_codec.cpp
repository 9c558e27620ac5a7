#include "dr/state_codec.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/scene.h"
#include "dr/bit_stream.h"

namespace zonesim::dr {

namespace {
constexpr double kSqrtHalf = 0.70710678118654752440;
// Kinds 0..4 (NPC, avatar, rigid body, emitter, unique item): three bits.
constexpr int kKindBits = 3, kOrderBits = 2, kSpinBits = 1, kLargestBits = 2;
constexpr std::uint64_t kMaxKind = 4;

int bitsFor(std::uint64_t codes) {
  int b = 1;
  while (b < 62 && (std::uint64_t{1} << b) < codes) ++b;
  return b;
}

/// [lo, lo + range] at a resolution: codes 0..ceil(range / resolution).
Quantiser span(double lo, double range, double resolution) {
  auto steps = std::uint64_t(std::ceil(range / resolution));
  return {lo, resolution, bitsFor(steps + 1)};
}

/// [-max, max] with zero exactly representable.
Quantiser symmetric(double max, double resolution) {
  double steps = std::ceil(max / resolution);
  return {-steps * resolution, resolution, bitsFor(std::uint64_t(2 * steps + 1))};
}

void writeV3(EncodedState& w, const Quantiser& q, const V3& v) {
  w.write(q.encode(v.x), q.bits);
  w.write(q.encode(v.y), q.bits);
  w.write(q.encode(v.z), q.bits);
}

V3 readV3(BitReader& r, const Quantiser& q) {
  V3 v;
  v.x = q.decode(r.read(q.bits));
  v.y = q.decode(r.read(q.bits));
  v.z = q.decode(r.read(q.bits));
  return v;
}
/// Appends a record's id and tick prefixes.
void writePrefix(BitWriter& w, std::uint64_t id, std::uint64_t tick, std::uint64_t prev_id,
                 std::uint64_t batch_tick) {
  w.writeVar(id - prev_id);
  w.writeVar(batch_tick - tick);
}

void append(BitWriter& w, const EncodedState& s) {
  for (int done = 0, k = 0; done < s.bits; done += 64, ++k)
    w.write(s.words[k], std::min(64, s.bits - done));
}

std::uint64_t idOf(const WireEntity& e) {
  return e.id;
}
std::uint64_t idOf(const EncodedEntity& e) {
  return e.id;
}

/// Streams of at most max_bytes into out[0..n), each record written by write(w, entity,
/// prev_id); returns n. out only grows, and its chunks' bytes are reused.
template <typename Entity, typename Write>
std::size_t packWith(std::span<const Entity> entities, std::size_t max_bytes,
                     std::vector<PackedChunk>& out, Write&& write) {
  std::size_t n = 0;
  auto storage = [&]() {
    return n < out.size() ? std::move(out[n].bytes) : std::vector<std::uint8_t>();
  };
  BitWriter w;
  w.reset(storage());
  std::size_t count = 0;
  std::uint64_t prev = 0;
  auto close = [&] {
    if (n == out.size()) out.emplace_back();
    out[n].bytes = w.take();
    out[n].count = count;
    ++n;
  };
  for (const Entity& e : entities) {
    std::size_t before = w.bits();
    write(w, e, prev);
    if (w.bytes().size() > max_bytes && count > 0) {
      // Did not fit: close this stream and start the next with the same entity.
      w.truncate(before);
      close();
      w.reset(storage());
      count = 0;
      write(w, e, 0);
    }
    ++count;
    prev = idOf(e);
  }
  if (count > 0)
    close();
  else if (n < out.size())
    out[n].bytes = w.take();  // handed back unused
  return n;
}
}  // namespace

CodecParams codecParams(const Scene& scene) {
  CodecParams p;
  const SceneBox& b = scene.world;
  p.world_min[0] = float(b.min.x), p.world_min[1] = float(b.min.y), p.world_min[2] = float(b.min.z);
  p.world_max[0] = float(b.max.x), p.world_max[1] = float(b.max.y), p.world_max[2] = float(b.max.z);
  p.cell_size = float(scene.interest_cell_size);
  const StateQuantisation& q = scene.dead_reckoning.quantisation;
  p.position_resolution = float(q.position_resolution);
  p.max_speed = float(q.max_speed);
  p.velocity_resolution = float(q.velocity_resolution);
  p.max_acceleration = float(q.max_acceleration);
  p.acceleration_resolution = float(q.acceleration_resolution);
  p.max_angular_velocity = float(q.max_angular_velocity);
  p.angular_velocity_resolution = float(q.angular_velocity_resolution);
  p.rotation_bits = std::uint8_t(q.rotation_bits);
  return p;
}

std::uint64_t Quantiser::encode(double v) const {
  double c = std::round((v - lo) / resolution);
  // Clamped in floating point: NaN and huge values must not overflow the conversion.
  if (!(c > 0)) return 0;
  double top = double(maxCode());
  return c >= top ? maxCode() : std::uint64_t(c);
}

StateCodec::StateCodec(const CodecParams& p) : params_(p) {
  double cell = p.cell_size;
  columns_ = std::max(1, int(std::ceil((double(p.world_max[0]) - p.world_min[0]) / cell)));
  rows_ = std::max(1, int(std::ceil((double(p.world_max[2]) - p.world_min[2]) / cell)));
  cell_bits_ = bitsFor(std::uint64_t(columns_) * std::uint64_t(rows_));
  // A quarter cell of slack each side: the entity may have moved since the cell was chosen.
  px_ = span(-0.25 * cell, 1.5 * cell, p.position_resolution);
  double height = double(p.world_max[1]) - p.world_min[1];
  py_ = span(double(p.world_min[1]) - 0.25 * height, 1.5 * height, p.position_resolution);
  vel_ = symmetric(p.max_speed, p.velocity_resolution);
  acc_ = symmetric(p.max_acceleration, p.acceleration_resolution);
  // Smallest-three components lie in [-1/sqrt2, 1/sqrt2]; an odd number of codes keeps 0.
  std::uint64_t half = (std::uint64_t{1} << (p.rotation_bits - 1)) - 1;
  rot_ = {-kSqrtHalf, kSqrtHalf / double(half), int(p.rotation_bits)};
  angvel_ = symmetric(p.max_angular_velocity, p.angular_velocity_resolution);
  int widest = stateBits({Order::Second, Spin::Rotating});
  if (widest > EncodedState::kMaxBits)
    throw std::invalid_argument(
        "state codec: a record's state takes " + std::to_string(widest) + " bits, more than " +
        std::to_string(EncodedState::kMaxBits) +
        "; coarsen the quantisation's resolutions or widen its ranges less");
}

Quantiser StateCodec::horizontal(int index_along, double world_min) const {
  Quantiser q = px_;
  q.lo = world_min + double(index_along) * double(params_.cell_size) + px_.lo;
  return q;
}

int StateCodec::stateBits(const Model& m) const {
  return fieldBits(m).total();
}

FieldBits StateCodec::fieldBits(const Model& m) const {
  FieldBits f;
  f.descriptor = kKindBits + kOrderBits + kSpinBits;
  f.position = cell_bits_ + 2 * px_.bits + py_.bits;
  if (m.order != Order::Static) f.velocity += 3 * vel_.bits;
  if (m.order == Order::Second) f.velocity += 3 * acc_.bits;
  f.orientation = kLargestBits + 3 * rot_.bits;
  if (m.spin == Spin::Rotating) f.orientation += 3 * angvel_.bits;
  return f;
}

FieldBits StateCodec::fieldBits(const EncodedState& s) const {
  // The model sits right after the kind, as encodeState writes it.
  const std::uint64_t order = (s.words[0] >> kKindBits) & ((1u << kOrderBits) - 1);
  const std::uint64_t spin = (s.words[0] >> (kKindBits + kOrderBits)) & ((1u << kSpinBits) - 1);
  return fieldBits({Order(order), Spin(spin)});
}

void smallestThree(const Q4& q, int& largest, double (&rest)[3], int force) {
  double c[4] = {q.x, q.y, q.z, q.w};
  largest = 0;
  for (int i = 1; i < 4; ++i)
    if (std::abs(c[i]) > std::abs(c[largest])) largest = i;
  // A forced index is honoured only where it is nearly the largest (a near tie), so that a
  // wrong hint cannot blow up the error of the other three.
  if (force >= 0 && force < 4 && std::abs(c[force]) >= std::abs(c[largest]) - 1e-3) largest = force;
  // q and -q are one rotation: make the dropped component positive.
  double sign = c[largest] < 0 ? -1.0 : 1.0;
  for (int i = 0, k = 0; i < 4; ++i)
    if (i != largest) rest[k++] = sign * c[i];
}

Q4 fromSmallestThree(int largest, const double (&rest)[3]) {
  double c[4];
  double sum = 0;
  for (int i = 0, k = 0; i < 4; ++i) {
    if (i == largest) continue;
    c[i] = rest[k++];
    sum += c[i] * c[i];
  }
  c[largest] = std::sqrt(std::max(0.0, 1.0 - sum));
  return normalized({c[0], c[1], c[2], c[3]});
}

State StateCodec::roundTrip(const State& s, const Model& m, int cell, int* largest) const {
  BitWriter w;
  WireEntity e;
  e.id = 1;
  e.cell = cell;
  e.model = m;
  e.state = s;
  write(w, e, 0, 0);
  BitReader r(w.bytes());
  WireEntity back = *read(r, 0, 0);
  if (largest != nullptr) *largest = back.rot_largest;
  return back.state;
}

void StateCodec::write(BitWriter& w, const WireEntity& e, std::uint64_t prev_id,
                       std::uint64_t batch_tick) const {
  writePrefix(w, e.id, e.tick, prev_id, batch_tick);
  append(w, encodeState(e));
}

void StateCodec::write(BitWriter& w, const EncodedEntity& e, std::uint64_t prev_id,
                       std::uint64_t batch_tick) const {
  writePrefix(w, e.id, e.tick, prev_id, batch_tick);
  append(w, *e.state);
}

EncodedState StateCodec::encodeState(const WireEntity& e) const {
  EncodedState w;
  w.write(e.kind, kKindBits);
  w.write(std::uint64_t(e.model.order), kOrderBits);
  w.write(std::uint64_t(e.model.spin), kSpinBits);
  int cell = std::clamp(e.cell, 0, cellCount() - 1);
  w.write(std::uint64_t(cell), cell_bits_);
  const State& s = e.state;
  w.write(horizontal(cell % columns_, params_.world_min[0]).encode(s.pos.x), px_.bits);
  w.write(py_.encode(s.pos.y), py_.bits);
  w.write(horizontal(cell / columns_, params_.world_min[2]).encode(s.pos.z), px_.bits);
  if (e.model.order != Order::Static) writeV3(w, vel_, s.vel);
  if (e.model.order == Order::Second) writeV3(w, acc_, s.acc);
  int largest;
  double rest[3];
  smallestThree(normalized(s.rot), largest, rest, e.rot_largest);
  w.write(std::uint64_t(largest), kLargestBits);
  for (double c : rest) w.write(rot_.encode(c), rot_.bits);
  if (e.model.spin == Spin::Rotating) writeV3(w, angvel_, s.angvel);
  return w;
}

std::optional<WireEntity> StateCodec::read(BitReader& r, std::uint64_t prev_id,
                                           std::uint64_t batch_tick) const {
  WireEntity e;
  std::uint64_t delta = r.readVar(), age = r.readVar();
  // Ids ascend strictly within a stream; a state cannot come from the future.
  if (delta == 0 || delta > ~prev_id || age > batch_tick) return std::nullopt;
  e.id = prev_id + delta;
  e.tick = batch_tick - age;
  const std::uint64_t kind = r.read(kKindBits);
  if (kind > kMaxKind) return std::nullopt;
  e.kind = std::uint8_t(kind);
  std::uint64_t order = r.read(kOrderBits);
  if (order > std::uint64_t(Order::Second)) return std::nullopt;
  e.model.order = Order(order);
  e.model.spin = Spin(r.read(kSpinBits));
  std::uint64_t cell = r.read(cell_bits_);
  if (cell >= std::uint64_t(cellCount())) return std::nullopt;
  e.cell = int(cell);
  State& s = e.state;
  s.pos.x = horizontal(e.cell % columns_, params_.world_min[0]).decode(r.read(px_.bits));
  s.pos.y = py_.decode(r.read(py_.bits));
  s.pos.z = horizontal(e.cell / columns_, params_.world_min[2]).decode(r.read(px_.bits));
  if (e.model.order != Order::Static) s.vel = readV3(r, vel_);
  if (e.model.order == Order::Second) s.acc = readV3(r, acc_);
  int largest = int(r.read(kLargestBits));
  e.rot_largest = largest;
  double rest[3];
  for (double& c : rest) c = rot_.decode(r.read(rot_.bits));
  s.rot = fromSmallestThree(largest, rest);
  if (e.model.spin == Spin::Rotating) s.angvel = readV3(r, angvel_);
  if (!r.ok()) return std::nullopt;
  return e;
}

std::size_t StateCodec::packInto(std::span<const WireEntity> entities, std::uint64_t batch_tick,
                                 std::size_t max_bytes, std::vector<PackedChunk>& chunks) const {
  return packWith(entities, max_bytes, chunks,
                  [&](BitWriter& w, const WireEntity& e, std::uint64_t prev) {
                    write(w, e, prev, batch_tick);
                  });
}

std::size_t StateCodec::packInto(std::span<const EncodedEntity> entities, std::uint64_t batch_tick,
                                 std::size_t max_bytes, std::vector<PackedChunk>& chunks) const {
  return packWith(entities, max_bytes, chunks,
                  [&](BitWriter& w, const EncodedEntity& e, std::uint64_t prev) {
                    write(w, e, prev, batch_tick);
                  });
}

std::vector<PackedChunk> StateCodec::pack(std::span<const WireEntity> entities,
                                          std::uint64_t batch_tick, std::size_t max_bytes) const {
  std::vector<PackedChunk> out;
  out.resize(packInto(entities, batch_tick, max_bytes, out));
  return out;
}

std::optional<std::vector<WireEntity>> StateCodec::unpack(std::span<const std::uint8_t> bytes,
                                                          std::size_t count,
                                                          std::uint64_t batch_tick) const {
  // Every record takes at least 20 bits: a count beyond that is a lie, not a reason to reserve.
  if (count > bytes.size() * 8 / 20) return std::nullopt;
  std::vector<WireEntity> out;
  out.reserve(count);
  BitReader r(bytes);
  std::uint64_t prev = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::optional<WireEntity> e = read(r, prev, batch_tick);
    if (!e) return std::nullopt;
    prev = e->id;
    out.push_back(*e);
  }
  // Only the padding of the last byte may remain.
  if (r.remaining() >= 8) return std::nullopt;
  return out;
}

}  // namespace zonesim::dr
