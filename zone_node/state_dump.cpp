#include "zone_node/state_dump.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "zone_node/cluster/entity_codec.h"
#include "zone_node/cluster/value_gather.h"

namespace zonesim::zone {

namespace {

const char* kindName(EntityKind k) {
  switch (k) {
    case EntityKind::Npc:
      return "npc";
    case EntityKind::Avatar:
      return "avatar";
    case EntityKind::RigidBody:
      return "rigid_body";
    case EntityKind::Emitter:
      return "emitter";
    case EntityKind::Item:
      return "item";
  }
  return "unknown";
}

// How the dump writes each value type, as JSON; %.17g round-trips doubles exactly: equal text
// means bitwise-equal state.
void writeValue(std::FILE* f, EntityId id) {
  std::fprintf(f, "%llu", (unsigned long long)id.value);
}
void writeValue(std::FILE* f, EntityKind k) {
  std::fprintf(f, "\"%s\"", kindName(k));
}
void writeValue(std::FILE* f, const Vec3& v) {
  std::fprintf(f, "[%.17g,%.17g,%.17g]", v.x(), v.y(), v.z());
}
void writeValue(std::FILE* f, const Quat& q) {
  std::fprintf(f, "[%.17g,%.17g,%.17g,%.17g]", q.x(), q.y(), q.z(), q.w());
}

/// The columns of kEntityColumns that the dump prints, under their names and in that list's
/// order: identity and motion, which every kind has. A column added here changes every dump,
/// and golden_states.py compares dumps byte for byte with reference dumps of earlier commits.
template <auto RecordMember>
constexpr bool kDumped = false;
// clang-format off
template <> constexpr bool kDumped<&EntityRecordData::id> = true;
template <> constexpr bool kDumped<&EntityRecordData::kind> = true;
template <> constexpr bool kDumped<&EntityRecordData::pos> = true;
template <> constexpr bool kDumped<&EntityRecordData::vel> = true;
template <> constexpr bool kDumped<&EntityRecordData::rot> = true;
// clang-format on

void writeLine(std::FILE* f, const EntityRecordData& e) {
  const char* separator = "{";
  forEachEntityColumn([&](const auto& c) {
    if constexpr (kDumped<std::remove_cvref_t<decltype(c)>::record>) {
      std::fprintf(f, "%s\"%s\":", separator, c.name);
      writeValue(f, e.*c.record);
      separator = ",";
    }
  });
  // Only where the scene's interactions touched it: every other scene's dump stays as it was.
  if (!(e.combat == CombatData{})) {
    const CombatData& c = e.combat;
    std::fprintf(f, ",\"combat\":[%.17g,%u,%u,%d,%u,%llu]", c.health, c.kills, c.deaths, c.items,
                 c.mail_seq, (unsigned long long)c.taken_at);
  }
  std::fputs("}\n", f);
}

void writeParticle(std::FILE* f, const std::array<double, 6>& q) {
  std::fputs("{\"kind\":\"particle\",\"pos\":", f);
  writeValue(f, Vec3(q[0], q[1], q[2]));
  std::fputs(",\"vel\":", f);
  writeValue(f, Vec3(q[3], q[4], q[5]));
  std::fputs("}\n", f);
}

}  // namespace

void dumpState(MPI_Comm comm, const EntityStore& store,
               const std::vector<std::array<double, 6>>& particles, const std::string& path) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  MigrationPayload mine;
  for (std::size_t i = 0; i < store.size(); ++i) mine.entities.push_back(store.record(i));
  std::vector<std::uint8_t> bytes = encodeMigration(mine);
  int n = int(bytes.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), displs(static_cast<std::size_t>(size));
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::vector<std::uint8_t> all;
  if (rank == 0) {
    int total = 0;
    for (int r = 0; r < size; ++r) {
      // Each segment starts aligned so that decodeMigration reads it in place.
      total = int((std::size_t(total) + kBatchAlign - 1) / kBatchAlign * kBatchAlign);
      displs[std::size_t(r)] = total;
      total += counts[std::size_t(r)];
    }
    all.resize(std::size_t(total));
  }
  MPI_Gatherv(bytes.data(), n, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, 0,
              comm);
  // Particles: six doubles each, sent as one flat list.
  const std::vector<double> flat_particles = gatherValuesToRoot(
      comm, {particles.empty() ? nullptr : particles.front().data(), particles.size() * 6});
  std::vector<std::array<double, 6>> all_particles(flat_particles.size() / 6);
  for (std::size_t i = 0; i < all_particles.size(); ++i)
    std::copy_n(flat_particles.begin() + std::ptrdiff_t(6 * i), 6, all_particles[i].begin());
  if (rank != 0) return;

  std::vector<EntityRecordData> entities;
  for (int r = 0; r < size; ++r) {
    MigrationPayload p = decodeMigration(std::span<const std::uint8_t>(
        all.data() + displs[std::size_t(r)], std::size_t(counts[std::size_t(r)])));
    entities.insert(entities.end(), p.entities.begin(), p.entities.end());
  }
  std::sort(entities.begin(), entities.end(),
            [](const auto& a, const auto& b) { return a.id < b.id; });
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  for (const EntityRecordData& e : entities) writeLine(f, e);
  std::sort(all_particles.begin(), all_particles.end());
  for (const auto& q : all_particles) writeParticle(f, q);
  std::fclose(f);
}

}  // namespace zonesim::zone
