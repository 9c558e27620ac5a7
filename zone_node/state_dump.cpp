#include "zone_node/state_dump.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "zone_node/cluster/entity_codec.h"

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
  }
  return "unknown";
}

void writeLine(std::FILE* f, const EntityRecordData& e) {
  // %.17g round-trips doubles exactly: equal text means bitwise-equal state.
  std::fprintf(
      f,
      "{\"id\":%llu,\"kind\":\"%s\",\"pos\":[%.17g,%.17g,%.17g],\"vel\":[%.17g,%.17g,%.17g],"
      "\"rot\":[%.17g,%.17g,%.17g,%.17g]}\n",
      (unsigned long long)e.id.value, kindName(e.kind), e.pos.x(), e.pos.y(), e.pos.z(), e.vel.x(),
      e.vel.y(), e.vel.z(), e.rot.x(), e.rot.y(), e.rot.z(), e.rot.w());
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
  // Particles: six doubles each, gathered the same way.
  int np = int(particles.size() * 6);
  std::vector<int> pcounts(static_cast<std::size_t>(size)), pdispls(static_cast<std::size_t>(size));
  MPI_Gather(&np, 1, MPI_INT, pcounts.data(), 1, MPI_INT, 0, comm);
  std::vector<std::array<double, 6>> all_particles;
  if (rank == 0) {
    int total = 0;
    for (int r = 0; r < size; ++r) {
      pdispls[std::size_t(r)] = total;
      total += pcounts[std::size_t(r)];
    }
    all_particles.resize(std::size_t(total) / 6);
  }
  MPI_Gatherv(particles.data(), np, MPI_DOUBLE, all_particles.data(), pcounts.data(),
              pdispls.data(), MPI_DOUBLE, 0, comm);
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
  for (const auto& q : all_particles)
    std::fprintf(
        f, "{\"kind\":\"particle\",\"pos\":[%.17g,%.17g,%.17g],\"vel\":[%.17g,%.17g,%.17g]}\n",
        q[0], q[1], q[2], q[3], q[4], q[5]);
  std::fclose(f);
}

}  // namespace zonesim::zone
