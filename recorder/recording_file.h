#pragma once
// The file around a recording's frames (idl/recording.fbs). Layout, little-endian:
//   "ZSREC" 0 0 1            8 bytes: magic and layout version 1
//   chunk*                   u32 length, u32 CRC-32 of the payload, payload (a Record
//                            FlatBuffer, zero-padded to a multiple of 8 so that every payload
//                            starts 8-aligned: its ulong fields are read in place)
//   u64 offset, "ZSRECEND"   16 bytes: where the last chunk (the Index) starts
// The first chunk is the Header, the last the Index; between them one frame per tick. A writer
// flushes after every frame, so a live reader (and a killed writer's file) has every frame but
// the last, cut one; only a finished file has its Index and footer. The Verifier checks
// structure, the CRC the bytes: a flipped bit inside a position passes the first only.

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace flatbuffers {
class FlatBufferBuilder;
}

namespace zonesim::recording {

struct Record;
struct Header;

/// A file that is not a complete, intact recording: names the file, the byte offset and why.
class RecordingError : public std::runtime_error {
 public:
  RecordingError(const std::string& path, std::uint64_t offset, const std::string& reason);
  std::uint64_t offset() const { return offset_; }

 private:
  std::uint64_t offset_;
};

inline constexpr char kMagic[8] = {'Z', 'S', 'R', 'E', 'C', 0, 0, 1};
inline constexpr char kFooterMagic[8] = {'Z', 'S', 'R', 'E', 'C', 'E', 'N', 'D'};
/// A frame larger than this is damage, not data (a zone of 1M sampled entities is 24 MB).
inline constexpr std::uint32_t kMaxChunkBytes = 256u << 20;

/// Appends frames to a new file; close() (or the destructor) writes the Index and the footer.
class RecordingWriter {
 public:
  /// Creates (truncates) path; throws std::runtime_error naming it if it cannot.
  explicit RecordingWriter(const std::string& path);
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  /// Writes the finished Record in `fbb` (FinishRecordBuffer) as the next chunk and flushes.
  /// `tick` is indexed unless the frame is the Header (`indexed` false).
  void write(const flatbuffers::FlatBufferBuilder& fbb, std::uint64_t tick, bool indexed = true);
  /// Writes the Index and the footer and closes the file (once; later calls do nothing).
  void close();
  /// Bytes written so far.
  std::uint64_t bytes() const { return offset_; }

 private:
  void writeChunk(const std::uint8_t* data, std::size_t size);

  std::string path_;
  std::FILE* file_ = nullptr;
  std::uint64_t offset_ = 0;
  std::vector<std::uint64_t> ticks_, offsets_;
};

/// A recording read whole into memory and checked: magic, every chunk's length and CRC, every
/// frame through the FlatBuffers Verifier, the Header first and the Index last and agreeing
/// with the frames. Anything else throws RecordingError.
class RecordingReader {
 public:
  /// `unfinished_ok`: accept a file without its Index and footer (still being written, or its
  /// writer was killed), ending at the last complete chunk; damage is refused all the same.
  explicit RecordingReader(const std::string& path, bool unfinished_ok = false);

  const Header& header() const;
  /// Tick frames (Header and Index excluded), in file order.
  std::size_t frames() const { return frames_.size(); }
  std::uint64_t tickOf(std::size_t i) const { return ticks_[i]; }
  const Record& frame(std::size_t i) const;
  /// Whether the file had its Index and footer.
  bool finished() const { return finished_; }

 private:
  std::string path_;
  std::vector<std::uint8_t> bytes_;
  std::size_t header_ = 0;
  std::vector<std::size_t> frames_;  // payload offsets
  std::vector<std::uint64_t> ticks_;
  bool finished_ = false;
};

}  // namespace zonesim::recording
