#include "zone_node/cluster/checkpoint.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace zonesim::zone {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("zs_ckpt_test_" + std::to_string(::getpid()));
  TempDir() { fs::remove_all(path); }
  ~TempDir() { fs::remove_all(path); }
};

EntityStore twoEntities() {
  EntityStore s;
  for (std::uint64_t c : {7u, 9u}) {
    EntityRecordData r;
    r.id = EntityId::make(0, c);
    r.pos = Vec3(double(c), 0, 1);
    s.add(r);
  }
  return s;
}

TEST(Checkpoint, RoundTripsEntitiesTickAndEveryCreatorsCounter) {
  TempDir dir;
  EntityStore store = twoEntities();
  // A run restarted on fewer ranks still remembers creator 3's counter: it must survive.
  std::map<std::uint32_t, std::uint64_t> inherited = {{0, 5}, {3, 41}};
  std::string folder =
      writeCheckpoint(MPI_COMM_WORLD, store, 120, 12, inherited, dir.path.string());
  EXPECT_EQ(fs::path(folder).filename(), "ckpt_120");
  CheckpointImage image = readCheckpoint(dir.path.string());  // through LATEST
  EXPECT_EQ(image.tick, 120u);
  ASSERT_EQ(image.entities.size(), 2u);
  EXPECT_EQ(image.entities[1].pos, store.pos[1]);
  EXPECT_EQ(image.id_counters.at(0), 12u);  // the larger of today's 12 and the inherited 5
  EXPECT_EQ(image.id_counters.at(3), 41u);
}

TEST(Checkpoint, AnIncompleteOrAlteredCheckpointIsRefused) {
  TempDir dir;
  EntityStore store = twoEntities();
  std::string folder = writeCheckpoint(MPI_COMM_WORLD, store, 1, 0, {}, dir.path.string());
  {
    std::fstream f(fs::path(folder) / "rank_0.rec",
                   std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(20);
    f.put('\x7f');  // one flipped byte: same size, another hash
  }
  EXPECT_THROW(readCheckpoint(folder), CheckpointError);
  fs::remove(fs::path(folder) / "MANIFEST.json");
  EXPECT_THROW(readCheckpoint(folder), CheckpointError);
}

}  // namespace
}  // namespace zonesim::zone
