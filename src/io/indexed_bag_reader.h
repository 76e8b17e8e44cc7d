// What the ROS 1 and MCAP readers share (private to src/io/): a message index built once, then
// messages served in recording-time order from a small cache of decompressed chunks; the
// decompressors of their chunks; little-endian field reads that name the file and offset on a
// short read.
#ifndef SPLINECAL_SRC_IO_INDEXED_BAG_READER_H_
#define SPLINECAL_SRC_IO_INDEXED_BAG_READER_H_

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <list>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "splinecal/io/bag_reader.h"

namespace splinecal {
namespace internal {

// A file read at explicit offsets (pread), so that several readers never share a position.
class BagFile {
 public:
  explicit BagFile(const std::string& path);
  ~BagFile();
  BagFile(const BagFile&) = delete;
  BagFile& operator=(const BagFile&) = delete;

  const std::string& path() const { return path_; }
  int64_t size() const { return size_; }
  // Reads exactly `bytes` at `offset`; throws "path: offset N: <what> ends past the end of the
  // file (truncated?)" when the file is shorter.
  void Read(int64_t offset, int64_t bytes, const char* what, std::string* out) const;
  // "path: offset N: message", for errors.
  [[noreturn]] void Fail(int64_t offset, const std::string& message) const;

 private:
  std::string path_;
  int fd_ = -1;
  int64_t size_ = 0;
};

// Little-endian reads from a byte range; out-of-range reads throw through the file's Fail with
// the absolute offset (`base` is the range's offset in the file, -1 inside a decompressed chunk:
// then the chunk's own offset is named).
class ByteCursor {
 public:
  ByteCursor(std::string_view bytes, const BagFile& file, int64_t base)
      : bytes_(bytes), file_(file), base_(base) {}

  template <typename T>
  T Get(const char* what) {
    Need(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  std::string_view Bytes(uint64_t count, const char* what) {
    Need(count, what);
    const std::string_view out = bytes_.substr(pos_, count);
    pos_ += count;
    return out;
  }
  void Need(uint64_t count, const char* what) const;
  size_t pos() const { return pos_; }
  void set_pos(size_t pos) { pos_ = pos; }
  size_t remaining() const { return bytes_.size() - pos_; }
  int64_t offset() const { return base_ + static_cast<int64_t>(pos_); }
  [[noreturn]] void Fail(const std::string& message) const { file_.Fail(offset(), message); }

 private:
  std::string_view bytes_;
  const BagFile& file_;
  int64_t base_;
  size_t pos_ = 0;
};

// Chunk decompression into `out` of exactly `size` bytes; throws through file.Fail(offset, ...)
// when the data is corrupt or decompresses to another size.
void DecompressBz2(std::string_view in, uint64_t size, const BagFile& file, int64_t offset,
                   std::string* out);
// The LZ4 *frame* format (ROS 1's roslz4 and MCAP both write frames, not raw blocks).
void DecompressLz4Frame(std::string_view in, uint64_t size, const BagFile& file, int64_t offset,
                        std::string* out);
void DecompressZstd(std::string_view in, uint64_t size, const BagFile& file, int64_t offset,
                    std::string* out);
// CRC-32 (ISO-HDLC, zlib's crc32), MCAP's checksum; `crc` continues a previous one.
uint32_t Crc32(std::string_view bytes, uint32_t crc = 0);

// Where one message is.
struct MessageRef {
  int64_t time_ns = 0;
  uint64_t chunk = 0;   // index into the reader's chunk list; kNoChunk for a message outside one
  uint64_t offset = 0;  // in the decompressed chunk, or in the file
  uint32_t file = 0;
  int32_t topic = 0;
};
inline constexpr uint64_t kNoChunk = ~uint64_t{0};

// A reader whose formats keep messages in (compressed) chunks. Subclasses fill topics_, refs_,
// files_ and implement LoadChunk and MessageAt.
class IndexedBagReader : public BagReader {
 public:
  void SelectTopics(const std::vector<int>& topics) override;
  bool Next(BagMessage* message) override;

 protected:
  // Sorts refs_ by time (stable: file order for ties), counts messages per topic and selects all
  // topics. Call once the index is complete.
  void FinishIndex();
  // The decompressed contents of chunk `chunk`.
  virtual void LoadChunk(uint64_t chunk, std::string* out) = 0;
  // The message bytes of `ref`: `chunk` is the decompressed chunk (empty for kNoChunk), `scratch`
  // a buffer the bytes may be read into.
  virtual std::string_view MessageAt(const MessageRef& ref, std::string_view chunk,
                                     std::string* scratch, std::string* where) = 0;

  std::vector<std::unique_ptr<BagFile>> files_;
  std::vector<MessageRef> refs_;

 private:
  const std::string& Chunk(uint64_t chunk);

  std::vector<bool> selected_;
  size_t next_ = 0;
  // The most recently used chunks, newest first. Messages of a time-ordered recording come from
  // one chunk after the other; a few cover chunks whose time ranges overlap.
  std::list<std::pair<uint64_t, std::string>> cache_;
  std::string scratch_;
};

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_IO_INDEXED_BAG_READER_H_
