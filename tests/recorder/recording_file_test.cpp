// The recording file (recorder/recording_file.h): frames written are read back as written, and
// a damaged or truncated file is refused with the offset and the reason.
#include "recorder/recording_file.h"

#include <flatbuffers/flatbuffers.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "recording_generated.h"

namespace zonesim::recording {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("zs_rec_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

void writeHeader(RecordingWriter& w) {
  flatbuffers::FlatBufferBuilder b;
  Rect world(0, 0, 100, 50);
  auto h = CreateHeader(b, 1, ProcessKind::Zone, 3, b.CreateString("test"), &world, 1.0 / 30, 0,
                        0, 25, 4, 2, b.CreateVectorOfStrings({"input", "ai"}), 0, 0, 1, 2, 60);
  FinishRecordBuffer(b, CreateRecord(b, Frame::Header, h.Union()));
  w.write(b, 60, false);
}

void writeTick(RecordingWriter& w, std::uint64_t tick, int entities) {
  flatbuffers::FlatBufferBuilder b;
  std::vector<EntitySample> e;
  for (int i = 0; i < entities; ++i)
    e.emplace_back(1000 + i, float(i), 0.5f, float(tick), std::int16_t(i % 2 ? 3 : 1),
                   std::uint8_t(i % 5), std::uint8_t(i % 2 ? 0 : 2));
  std::vector<Event> ev{Event(1000, 0, 1, EventKind::Departed),
                        Event(0, tick, 0, EventKind::Checkpoint)};
  Rect r(50, 0, 100, 50);
  std::vector<float> phases{0.25f, 1.5f};
  auto z = CreateZoneTick(b, tick, tick / 30.0, 2, &r, b.CreateVectorOfStructs(e),
                          std::uint32_t(entities / 2), b.CreateVectorOfStructs(ev),
                          b.CreateVector(phases), 0, 2.0f);
  FinishRecordBuffer(b, CreateRecord(b, Frame::ZoneTick, z.Union()));
  w.write(b, tick);
}

// A finished file of a Header and 3 ticks (60, 61, 62); returns its bytes.
std::vector<char> writeSample(const std::string& path) {
  {
    RecordingWriter w(path);
    writeHeader(w);
    for (std::uint64_t t = 60; t < 63; ++t) writeTick(w, t, 7 + int(t) % 3);
  }
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Where each chunk of a finished file starts, walking the lengths from the first.
std::vector<std::size_t> chunkOffsets(const std::vector<char>& bytes) {
  std::vector<std::size_t> chunks;
  for (std::size_t at = 8; at + 8 <= bytes.size() - 16;) {
    chunks.push_back(at);
    std::uint32_t size;
    std::memcpy(&size, bytes.data() + at, 4);
    at += 8 + size;
  }
  return chunks;
}

void save(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// The error a reading of `bytes` gives, or "" if it reads.
std::string refusal(const std::vector<char>& bytes, std::uint64_t* offset = nullptr,
                    bool unfinished_ok = false) {
  const std::string path = tempPath("damaged.zsrec");
  save(path, bytes);
  try {
    RecordingReader r(path, unfinished_ok);
  } catch (const RecordingError& e) {
    if (offset) *offset = e.offset();
    std::filesystem::remove(path);
    return e.what();
  }
  std::filesystem::remove(path);
  return "";
}

TEST(RecordingFile, FramesReadBackAsWritten) {
  const std::string path = tempPath("roundtrip.zsrec");
  writeSample(path);
  RecordingReader r(path);
  EXPECT_TRUE(r.finished());
  const Header& h = r.header();
  EXPECT_EQ(h.index(), 3);
  EXPECT_EQ(h.scene()->str(), "test");
  EXPECT_EQ(h.grid_cols(), 4);
  EXPECT_EQ(h.phase_names()->size(), 2u);
  EXPECT_EQ(h.start_tick(), 60u);
  ASSERT_EQ(r.frames(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const std::uint64_t tick = 60 + i;
    EXPECT_EQ(r.tickOf(i), tick);
    const ZoneTick* z = r.frame(i).frame_as_ZoneTick();
    ASSERT_NE(z, nullptr);
    EXPECT_EQ(z->tick(), tick);
    EXPECT_EQ(z->epoch(), 2u);
    EXPECT_FLOAT_EQ(z->rect()->min_x(), 50);
    const int n = 7 + int(tick) % 3;
    ASSERT_EQ(z->entities()->size(), std::size_t(n));
    const EntitySample* last = z->entities()->Get(std::size_t(n - 1));
    EXPECT_EQ(last->id(), std::uint64_t(1000 + n - 1));
    EXPECT_FLOAT_EQ(last->z(), float(tick));
    EXPECT_EQ(last->kind(), std::uint8_t((n - 1) % 5));
    EXPECT_EQ(z->events()->Get(1)->kind(), EventKind::Checkpoint);
    EXPECT_EQ(z->events()->Get(1)->value(), tick);
    EXPECT_FLOAT_EQ(z->phase_ms()->Get(1), 1.5f);
  }
  std::filesystem::remove(path);
}

TEST(RecordingFile, AFlippedBitIsRefusedAtItsChunk) {
  const std::string path = tempPath("flip.zsrec");
  std::vector<char> bytes = writeSample(path);
  std::filesystem::remove(path);
  const std::vector<std::size_t> chunks = chunkOffsets(bytes);
  ASSERT_EQ(chunks.size(), 5u);  // Header, 3 ticks, Index
  std::vector<char> damaged = bytes;
  damaged[chunks[2] + 8 + 40] ^= 0x10;
  std::uint64_t offset = 0;
  EXPECT_NE(refusal(damaged, &offset).find("CRC mismatch"), std::string::npos);
  EXPECT_EQ(offset, chunks[2]);
  // Damage is refused even where an unfinished file is accepted.
  EXPECT_NE(refusal(damaged, nullptr, true).find("CRC mismatch"), std::string::npos);
}

TEST(RecordingFile, TruncatedFilesAreRefusedOrReadToTheirLastCompleteFrame) {
  const std::string path = tempPath("cut.zsrec");
  std::vector<char> bytes = writeSample(path);
  std::filesystem::remove(path);
  // Cut inside the third tick frame: no footer, and a partial chunk.
  const std::vector<std::size_t> chunks = chunkOffsets(bytes);
  std::vector<char> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(chunks[3] + 20));
  std::uint64_t offset = 0;
  const std::string why = refusal(cut, &offset);
  EXPECT_NE(why.find("truncated chunk"), std::string::npos) << why;
  EXPECT_EQ(offset, chunks[3]);
  // A live reader (or one reading a killed writer's file) takes the complete frames.
  const std::string cut_path = tempPath("cut_ok.zsrec");
  save(cut_path, cut);
  RecordingReader r(cut_path, /*unfinished_ok=*/true);
  EXPECT_FALSE(r.finished());
  EXPECT_EQ(r.frames(), 2u);
  std::filesystem::remove(cut_path);
  // Cut at a chunk boundary: every frame is whole, but the Index is missing.
  std::vector<char> no_index(bytes.begin(), bytes.begin() + std::ptrdiff_t(chunks[4]));
  EXPECT_NE(refusal(no_index, &offset).find("no Index"), std::string::npos);
  EXPECT_EQ(offset, chunks[4]);
}

TEST(RecordingFile, OtherFilesAndBadStructureAreRefusedByName) {
  const std::string path = tempPath("other.zsrec");
  std::vector<char> bytes = writeSample(path);
  std::filesystem::remove(path);
  std::vector<char> not_ours(bytes);
  not_ours[0] = 'X';
  EXPECT_NE(refusal(not_ours).find("offset 0: not a zonesim recording"), std::string::npos);
  std::vector<char> newer(bytes);
  newer[7] = 2;
  EXPECT_NE(refusal(newer).find("layout version 2"), std::string::npos);
  // A chunk length that is not a frame's.
  std::vector<char> bad_length(bytes);
  const std::uint32_t huge = 0x7FFFFFF8u;
  std::memcpy(bad_length.data() + 8, &huge, 4);
  EXPECT_NE(refusal(bad_length).find("is not a frame's"), std::string::npos);
  // A footer pointing nowhere.
  std::vector<char> bad_footer(bytes);
  const std::uint64_t nowhere = 3;
  std::memcpy(bad_footer.data() + bad_footer.size() - 16, &nowhere, 8);
  EXPECT_NE(refusal(bad_footer).find("footer points outside the file"), std::string::npos);
  // An empty file and a missing one.
  EXPECT_NE(refusal({}).find("not a zonesim recording"), std::string::npos);
  EXPECT_THROW(RecordingReader(tempPath("missing.zsrec")), RecordingError);
}

}  // namespace
}  // namespace zonesim::recording
