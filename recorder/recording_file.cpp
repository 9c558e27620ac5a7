#include "recorder/recording_file.h"

#include <flatbuffers/flatbuffers.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "recorder/crc32.h"
#include "recording_generated.h"

namespace zonesim::recording {

namespace {

constexpr std::size_t kChunkHeaderBytes = 8;
constexpr std::size_t kFooterBytes = 16;

std::uint32_t readU32(const std::uint8_t* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

std::uint64_t readU64(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

std::uint64_t tickOfFrame(const Record& r) {
  if (const ZoneTick* z = r.frame_as_ZoneTick()) return z->tick();
  if (const GatewayTick* g = r.frame_as_GatewayTick()) return g->tick();
  return 0;
}

}  // namespace

RecordingError::RecordingError(const std::string& path, std::uint64_t offset,
                               const std::string& reason)
    : std::runtime_error(path + ": offset " + std::to_string(offset) + ": " + reason),
      offset_(offset) {}

// ---- Writer ----

RecordingWriter::RecordingWriter(const std::string& path) : path_(path) {
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
  std::fwrite(kMagic, 1, sizeof kMagic, file_);
  offset_ = sizeof kMagic;
}

RecordingWriter::~RecordingWriter() { close(); }

void RecordingWriter::writeChunk(const std::uint8_t* data, std::size_t size) {
  static constexpr std::uint8_t kZeros[8] = {};
  const std::size_t padded = (size + 7) / 8 * 8;
  std::uint32_t head[2] = {std::uint32_t(padded), 0};
  // The CRC covers the padding too: the reader checks exactly the bytes it keeps.
  std::vector<std::uint8_t> scratch;
  const std::uint8_t* payload = data;
  if (padded != size) {
    scratch.assign(data, data + size);
    scratch.resize(padded, 0);
    payload = scratch.data();
  }
  head[1] = crc32(payload, padded);
  std::fwrite(head, 1, sizeof head, file_);
  std::fwrite(data, 1, size, file_);
  std::fwrite(kZeros, 1, padded - size, file_);
  offset_ += kChunkHeaderBytes + padded;
}

void RecordingWriter::write(const flatbuffers::FlatBufferBuilder& fbb, std::uint64_t tick,
                            bool indexed) {
  if (!file_) return;
  if (indexed) {
    ticks_.push_back(tick);
    offsets_.push_back(offset_);
  }
  writeChunk(fbb.GetBufferPointer(), fbb.GetSize());
  // A live inspector reads what is flushed; a killed writer loses at most the frame it was on.
  std::fflush(file_);
}

void RecordingWriter::close() {
  if (!file_) return;
  flatbuffers::FlatBufferBuilder fbb(64 + 16 * ticks_.size());
  auto index = CreateIndex(fbb, fbb.CreateVector(ticks_), fbb.CreateVector(offsets_));
  FinishRecordBuffer(fbb, CreateRecord(fbb, Frame::Index, index.Union()));
  const std::uint64_t index_at = offset_;
  writeChunk(fbb.GetBufferPointer(), fbb.GetSize());
  std::fwrite(&index_at, 1, 8, file_);
  std::fwrite(kFooterMagic, 1, sizeof kFooterMagic, file_);
  std::fclose(file_);
  file_ = nullptr;
}

// ---- Reader ----

RecordingReader::RecordingReader(const std::string& path, bool unfinished_ok) : path_(path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RecordingError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  bytes_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const std::size_t n = bytes_.size();
  auto fail = [&](std::uint64_t at, const std::string& why) { throw RecordingError(path, at, why); };
  if (n < sizeof kMagic || std::memcmp(bytes_.data(), kMagic, 5) != 0)
    fail(0, "not a zonesim recording (no ZSREC magic)");
  if (std::memcmp(bytes_.data(), kMagic, sizeof kMagic) != 0)
    fail(5, "layout version " + std::to_string(bytes_[7]) + " is not 1");

  // The footer, if any, says where the chunks end.
  std::size_t end = n;
  std::uint64_t index_at = 0;
  if (n >= sizeof kMagic + kFooterBytes &&
      std::memcmp(bytes_.data() + n - 8, kFooterMagic, sizeof kFooterMagic) == 0) {
    finished_ = true;
    end = n - kFooterBytes;
    index_at = readU64(bytes_.data() + end);
    if (index_at < sizeof kMagic || index_at >= end)
      fail(end, "footer points outside the file (" + std::to_string(index_at) + ")");
  }

  std::size_t at = sizeof kMagic;
  bool has_header = false, has_index = false;
  while (at < end) {
    if (has_index) fail(at, "data after the Index frame");
    if (end - at < kChunkHeaderBytes) {
      if (unfinished_ok && !finished_) break;
      fail(at, "truncated chunk header (" + std::to_string(end - at) + " bytes left)");
    }
    const std::uint32_t size = readU32(bytes_.data() + at);
    const std::uint32_t crc = readU32(bytes_.data() + at + 4);
    if (size == 0 || size % 8 != 0 || size > kMaxChunkBytes)
      fail(at, "chunk length " + std::to_string(size) + " is not a frame's");
    if (end - at - kChunkHeaderBytes < size) {
      if (unfinished_ok && !finished_) break;
      fail(at, "truncated chunk: " + std::to_string(size) + " bytes announced, " +
                   std::to_string(end - at - kChunkHeaderBytes) + " left");
    }
    const std::uint8_t* payload = bytes_.data() + at + kChunkHeaderBytes;
    if (crc32(payload, size) != crc) fail(at, "chunk CRC mismatch (damaged bytes)");
    flatbuffers::Verifier verifier(payload, size);
    if (!VerifyRecordBuffer(verifier)) fail(at, "frame fails FlatBuffers verification");
    const Record& r = *GetRecord(payload);
    const std::size_t payload_at = at + kChunkHeaderBytes;
    switch (r.frame_type()) {
      case Frame::Header:
        if (has_header) fail(at, "a second Header frame");
        if (r.frame_as_Header()->version() != 1)
          fail(at, "header version " + std::to_string(r.frame_as_Header()->version()) + " is not 1");
        has_header = true;
        header_ = payload_at;
        break;
      case Frame::ZoneTick:
      case Frame::GatewayTick:
        if (!has_header) fail(at, "a tick frame before the Header");
        frames_.push_back(payload_at);
        ticks_.push_back(tickOfFrame(r));
        break;
      case Frame::Index: {
        if (!finished_ || at != index_at) fail(at, "an Index frame that the footer does not name");
        const Index& ix = *r.frame_as_Index();
        if (!ix.ticks() || !ix.offsets() || ix.ticks()->size() != frames_.size() ||
            ix.offsets()->size() != frames_.size())
          fail(at, "the Index lists " + std::to_string(ix.ticks() ? ix.ticks()->size() : 0) +
                       " frames, the file holds " + std::to_string(frames_.size()));
        for (std::size_t i = 0; i < frames_.size(); ++i)
          if (ix.offsets()->Get(i) + kChunkHeaderBytes != frames_[i] ||
              ix.ticks()->Get(i) != ticks_[i])
            fail(at, "the Index disagrees with frame " + std::to_string(i));
        has_index = true;
        break;
      }
      default:
        fail(at, "a frame of unknown type " + std::to_string(int(r.frame_type())));
    }
    at += kChunkHeaderBytes + size;
  }
  if (!has_header) fail(sizeof kMagic, "no Header frame");
  if (!has_index && !unfinished_ok)
    fail(at, "no Index: the file ends without its footer (its writer did not finish)");
  if (finished_ && !has_index) fail(index_at, "the footer names no Index frame");
}

const Header& RecordingReader::header() const {
  return *GetRecord(bytes_.data() + header_)->frame_as_Header();
}

const Record& RecordingReader::frame(std::size_t i) const {
  return *GetRecord(bytes_.data() + frames_.at(i));
}

}  // namespace zonesim::recording
