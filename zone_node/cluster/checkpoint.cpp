#include "zone_node/cluster/checkpoint.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/entity_id.h"
#include "zone_node/cluster/entity_codec.h"

namespace zonesim::zone {

namespace fs = std::filesystem;

namespace {

constexpr int kFormat = 1;

std::string hex(std::uint64_t v) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)v);
  return buf;
}

/// Writes bytes to path atomically: temporary file, fsync, rename, fsync of the folder.
void writeAtomically(const fs::path& path, const void* data, std::size_t size) {
  fs::path tmp = path;
  tmp += ".tmp";
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw CheckpointError("cannot create " + tmp.string() + ": " + std::strerror(errno));
  const auto* p = static_cast<const std::uint8_t*>(data);
  std::size_t left = size;
  while (left > 0) {
    ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      throw CheckpointError("cannot write " + tmp.string() + ": " + std::strerror(errno));
    }
    p += n;
    left -= std::size_t(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0)
    throw CheckpointError("cannot sync " + tmp.string() + ": " + std::strerror(errno));
  fs::rename(tmp, path);
  int dfd = ::open(path.parent_path().c_str(), O_RDONLY | O_DIRECTORY);
  if (dfd >= 0) {
    ::fsync(dfd);  // the rename itself must survive a crash
    ::close(dfd);
  }
}

void writeText(const fs::path& path, const std::string& text) {
  writeAtomically(path, text.data(), text.size());
}

std::vector<std::uint8_t> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError("cannot read " + path.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string rankFile(int rank) {
  return "rank_" + std::to_string(rank) + ".rec";
}

}  // namespace

std::uint64_t fnv1a64(const std::uint8_t* data, std::size_t size) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= data[i];
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::string writeCheckpoint(MPI_Comm comm, const EntityStore& store, std::uint64_t tick,
                            std::uint64_t ids_issued,
                            const std::map<std::uint32_t, std::uint64_t>& inherited,
                            const std::string& dir) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  fs::path folder = fs::path(dir) / ("ckpt_" + std::to_string(tick));
  if (rank == 0) fs::create_directories(folder);
  MPI_Barrier(comm);

  MigrationPayload mine;
  mine.tick = tick;
  mine.from_rank = rank;
  IdSetDigest digest;
  for (std::size_t i = 0; i < store.size(); ++i) {
    mine.entities.push_back(store.record(i));
    digest.add(store.id[i]);
  }
  std::vector<std::uint8_t> bytes = encodeMigration(mine);
  // A rank that fails to write says so through the gather below rather than leaving the
  // others waiting; the manifest is then never written.
  std::uint64_t ok = 1;
  std::string error;
  try {
    writeAtomically(folder / rankFile(rank), bytes.data(), bytes.size());
  } catch (const std::exception& e) {
    ok = 0;
    error = e.what();
  }
  std::uint64_t row[6] = {ok,           bytes.size(), fnv1a64(bytes.data(), bytes.size()),
                          digest.count, digest.hash,  ids_issued};
  std::vector<std::uint64_t> rows(std::size_t(size) * 6);
  MPI_Gather(row, 6, MPI_UINT64_T, rows.data(), 6, MPI_UINT64_T, 0, comm);

  std::uint64_t all_ok = 1;
  if (rank == 0) {
    nlohmann::json m;
    m["format"] = kFormat;
    m["tick"] = tick;
    m["ranks"] = size;
    IdSetDigest total;
    std::map<std::uint32_t, std::uint64_t> counters = inherited;
    for (int r = 0; r < size; ++r) {
      const std::uint64_t* x = &rows[std::size_t(r) * 6];
      all_ok &= x[0];
      m["files"].push_back({{"name", rankFile(r)}, {"bytes", x[1]}, {"fnv1a64", hex(x[2])}});
      std::uint64_t& c = counters[std::uint32_t(r)];
      c = std::max(c, x[5]);
      total.merge({x[3], x[4]});
    }
    for (const auto& [creator, issued] : counters)
      m["id_counters"][std::to_string(creator)] = issued;
    m["entities"] = total.count;
    m["id_hash"] = hex(total.hash);
    if (all_ok) {
      writeText(folder / "MANIFEST.json", m.dump(1) + "\n");
      writeText(fs::path(dir) / "LATEST", folder.filename().string() + "\n");
    }
  }
  MPI_Bcast(&all_ok, 1, MPI_UINT64_T, 0, comm);
  if (!ok) throw CheckpointError(error);
  if (!all_ok)
    throw CheckpointError("checkpoint " + folder.string() + " incomplete: a rank failed to write");
  return folder.string();
}

CheckpointImage readCheckpoint(const std::string& path) {
  fs::path folder(path);
  if (fs::exists(folder / "LATEST")) {
    std::string name;
    std::ifstream(folder / "LATEST") >> name;
    folder /= name;
  }
  fs::path manifest_path = folder / "MANIFEST.json";
  if (!fs::exists(manifest_path))
    throw CheckpointError(folder.string() + ": no MANIFEST.json (incomplete or not a checkpoint)");
  nlohmann::json m;
  try {
    m = nlohmann::json::parse(readBytes(manifest_path));
  } catch (const nlohmann::json::exception& e) {
    throw CheckpointError(manifest_path.string() + ": " + e.what());
  }
  if (m.value("format", 0) != kFormat)
    throw CheckpointError(manifest_path.string() + ": unknown format");

  CheckpointImage image;
  image.path = folder.string();
  image.tick = m.at("tick").get<std::uint64_t>();
  image.ranks = m.at("ranks").get<int>();
  IdSetDigest digest;
  for (const auto& f : m.at("files")) {
    fs::path file = folder / f.at("name").get<std::string>();
    std::vector<std::uint8_t> bytes = readBytes(file);
    if (bytes.size() != f.at("bytes").get<std::uint64_t>() ||
        hex(fnv1a64(bytes.data(), bytes.size())) != f.at("fnv1a64").get<std::string>())
      throw CheckpointError(file.string() + ": size or hash differs from the manifest");
    MigrationPayload p;
    try {
      p = decodeMigration(bytes);
    } catch (const CodecError& e) {
      throw CheckpointError(file.string() + ": " + e.what());
    }
    for (EntityRecordData& e : p.entities) {
      digest.add(e.id);
      image.entities.push_back(std::move(e));
    }
  }
  for (const auto& [creator, issued] : m.at("id_counters").items())
    image.id_counters[std::uint32_t(std::stoul(creator))] = issued.get<std::uint64_t>();
  if (digest.count != m.at("entities").get<std::uint64_t>() ||
      hex(digest.hash) != m.at("id_hash").get<std::string>())
    throw CheckpointError(folder.string() +
                          ": entities disagree with the manifest's count or id hash");
  return image;
}

}  // namespace zonesim::zone
