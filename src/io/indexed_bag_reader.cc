#include "indexed_bag_reader.h"

#include <bzlib.h>
#include <fcntl.h>
#include <lz4frame.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cerrno>
#include <limits>

#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace internal {

BagFile::BagFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error(path, 0, std::string("cannot open: ") + std::strerror(errno));
  struct stat info;
  if (::fstat(fd_, &info) != 0 || S_ISDIR(info.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw Error(path, 0, "is a directory or unreadable, expected a bag file");
  }
  size_ = info.st_size;
}

BagFile::~BagFile() {
  if (fd_ >= 0) ::close(fd_);
}

void BagFile::Fail(int64_t offset, const std::string& message) const {
  throw Error(path_, 0, StringPrintf("offset %lld: ", static_cast<long long>(offset)) + message);
}

void BagFile::Read(int64_t offset, int64_t bytes, const char* what, std::string* out) const {
  if (offset < 0 || bytes < 0 || offset > size_ || bytes > size_ - offset) {
    Fail(offset, StringPrintf("%s of %lld bytes ends past the end of the file (%lld bytes): "
                              "truncated?",
                              what, static_cast<long long>(bytes), static_cast<long long>(size_)));
  }
  out->resize(static_cast<size_t>(bytes));
  int64_t done = 0;
  while (done < bytes) {
    const ssize_t got = ::pread(fd_, out->data() + done, static_cast<size_t>(bytes - done),
                                static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) Fail(offset + done, std::string("read failed: ") + std::strerror(errno));
    done += got;
  }
}

void ByteCursor::Need(uint64_t count, const char* what) const {
  if (count > remaining()) {
    Fail(StringPrintf("%s (%llu bytes) runs past the end of its record (%zu bytes left)", what,
                      static_cast<unsigned long long>(count), remaining()));
  }
}

namespace {

// Chunks larger than this are refused before allocating: far beyond the few MB writers use
// (rosbag: 768 KiB, MCAP writers: 1-4 MiB), small enough that a corrupt size cannot take the
// machine's memory.
constexpr uint64_t kMaxChunkBytes = uint64_t{1} << 29;

void CheckChunkSize(uint64_t size, const BagFile& file, int64_t offset) {
  if (size > kMaxChunkBytes) {
    file.Fail(offset, StringPrintf("chunk claims %llu uncompressed bytes (more than 512 MiB): "
                                   "corrupt chunk header",
                                   static_cast<unsigned long long>(size)));
  }
}

void WrongSize(uint64_t got, uint64_t size, const BagFile& file, int64_t offset) {
  file.Fail(offset, StringPrintf("chunk decompresses to %llu bytes, its header says %llu",
                                 static_cast<unsigned long long>(got),
                                 static_cast<unsigned long long>(size)));
}

// A chunk of `size` announced bytes decompressed into *out: `decompress` writes into a buffer one
// byte larger than announced (to tell a chunk that decompresses to more from an exact one) and
// returns how many bytes it wrote, which must be `size`.
template <typename Decompress>
void DecompressChunk(uint64_t size,
                     const BagFile& file,
                     int64_t offset,
                     std::string* out,
                     const Decompress& decompress) {
  CheckChunkSize(size, file, offset);
  out->resize(size + 1);
  const uint64_t got = decompress();
  if (got != size) WrongSize(got, size, file, offset);
  out->resize(size);
}

}  // namespace

void DecompressBz2(
    std::string_view in, uint64_t size, const BagFile& file, int64_t offset, std::string* out) {
  DecompressChunk(size, file, offset, out, [&]() -> uint64_t {
    unsigned int got = static_cast<unsigned int>(out->size());
    const int status = BZ2_bzBuffToBuffDecompress(out->data(),
                                                  &got,
                                                  const_cast<char*>(in.data()),
                                                  static_cast<unsigned int>(in.size()),
                                                  0,
                                                  0);
    if (status == BZ_OUTBUFF_FULL) return size + 1;
    if (status != BZ_OK) {
      file.Fail(offset, StringPrintf("bz2 chunk does not decompress (libbz2 error %d)", status));
    }
    return got;
  });
}

void DecompressLz4Frame(
    std::string_view in, uint64_t size, const BagFile& file, int64_t offset, std::string* out) {
  DecompressChunk(size, file, offset, out, [&]() -> uint64_t {
    LZ4F_dctx* context = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION))) {
      throw std::bad_alloc();
    }
    size_t in_done = 0;
    size_t out_done = 0;
    size_t status = 1;
    while (status != 0 && in_done < in.size() && out_done < out->size()) {
      size_t in_size = in.size() - in_done;
      size_t out_size = out->size() - out_done;
      status = LZ4F_decompress(
          context, out->data() + out_done, &out_size, in.data() + in_done, &in_size, nullptr);
      if (LZ4F_isError(status)) {
        const std::string name = LZ4F_getErrorName(status);
        LZ4F_freeDecompressionContext(context);
        file.Fail(offset, "lz4 chunk does not decompress (" + name + ")");
      }
      in_done += in_size;
      out_done += out_size;
    }
    LZ4F_freeDecompressionContext(context);
    if (status != 0 && out_done <= size) {
      file.Fail(offset, "lz4 chunk ends inside its frame (truncated chunk)");
    }
    return out_done;
  });
}

void DecompressZstd(
    std::string_view in, uint64_t size, const BagFile& file, int64_t offset, std::string* out) {
  DecompressChunk(size, file, offset, out, [&]() -> uint64_t {
    const size_t got = ZSTD_decompress(out->data(), out->size(), in.data(), in.size());
    if (ZSTD_isError(got)) {
      file.Fail(offset,
                std::string("zstd chunk does not decompress (") + ZSTD_getErrorName(got) + ")");
    }
    return got;
  });
}

uint32_t Crc32(std::string_view bytes, uint32_t crc) {
  // zlib's crc32 (the same CRC): several GB/s where a byte-wise table did 0.4 GB/s, which held
  // MCAP reading to 85 MB/s (bench/bag_bench.cc, docs/bags.md "Speed").
  return static_cast<uint32_t>(
      crc32_z(crc, reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
}

void AddTopicStatistics(int topic_index, int64_t time_ns, std::vector<BagTopic>* topics) {
  BagTopic& topic = (*topics)[topic_index];
  if (topic.message_count == 0) {
    topic.first_time_ns = time_ns;
  } else {
    topic.max_gap_ns = std::max(topic.max_gap_ns, time_ns - topic.last_time_ns);
  }
  topic.last_time_ns = time_ns;
  ++topic.message_count;
}

void IndexedBagReader::FinishIndex() {
  std::stable_sort(refs_.begin(), refs_.end(), [](const MessageRef& a, const MessageRef& b) {
    return a.time_ns < b.time_ns;
  });
  for (BagTopic& topic : topics_) topic.message_count = 0;
  for (const MessageRef& ref : refs_) AddTopicStatistics(ref.topic, ref.time_ns, &topics_);
  for (const auto& file : files_) file_bytes_ += file->size();
  selected_.assign(topics_.size(), true);
}

void IndexedBagReader::SelectTopics(const std::vector<int>& topics) {
  selected_.assign(topics_.size(), false);
  for (const int topic : topics) selected_.at(topic) = true;
  next_ = 0;
}

const std::string& IndexedBagReader::Chunk(uint64_t chunk) {
  for (auto it = cache_.begin(); it != cache_.end(); ++it) {
    if (it->first == chunk) {
      cache_.splice(cache_.begin(), cache_, it);
      return cache_.front().second;
    }
  }
  constexpr size_t kCachedChunks = 4;
  if (cache_.size() >= kCachedChunks) {
    cache_.splice(cache_.begin(), cache_, std::prev(cache_.end()));  // reuse its buffer
    cache_.front().first = kNoChunk;
  } else {
    cache_.emplace_front(kNoChunk, std::string());
  }
  LoadChunk(chunk, &cache_.front().second);
  cache_.front().first = chunk;
  return cache_.front().second;
}

bool IndexedBagReader::Next(BagMessage* message) {
  while (next_ < refs_.size() && !selected_[refs_[next_].topic]) ++next_;
  if (next_ == refs_.size()) return false;
  const MessageRef& ref = refs_[next_++];
  const std::string_view chunk = ref.chunk == kNoChunk ? std::string_view() : Chunk(ref.chunk);
  message->topic = ref.topic;
  message->receive_time_ns = ref.time_ns;
  message->data = MessageAt(ref, chunk, &scratch_, &message->where);
  return true;
}

}  // namespace internal

int BagReader::FindTopic(const std::string& name) const {
  for (size_t i = 0; i < topics_.size(); ++i) {
    if (topics_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace splinecal
