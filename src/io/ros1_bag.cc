// ROS 1 bag format 2.0 (wiki.ros.org/Bags/Format/2.0): records of a header (name=value fields,
// "op" the record type) and data. Messages (op 2) and connections (op 7) sit in chunks (op 5,
// compressed "none", "bz2" or "lz4"); each chunk is followed by one index record (op 4) per
// connection giving each message's time and offset in the decompressed chunk; a closed bag ends
// with its connections and chunk infos (op 6), pointed at by the bag header's index_pos.
#include <map>
#include <utility>

#include "bag_formats.h"
#include "indexed_bag_reader.h"
#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace internal {
namespace {

constexpr std::string_view kMagic = "#ROSBAG V2.0\n";
enum Op : uint8_t {
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};
// A record header larger than this is corrupt: real ones hold a few short fields (a connection's
// message definition lives in its data, not its header).
constexpr int64_t kMaxHeaderBytes = 1 << 20;

// A record header's fields.
class RecordHeader {
 public:
  RecordHeader(std::string_view bytes, const BagFile& file, int64_t offset) {
    ByteCursor cursor(bytes, file, offset);
    while (cursor.remaining() > 0) {
      const uint32_t length = cursor.Get<uint32_t>("header field length");
      const std::string_view field = cursor.Bytes(length, "header field");
      const size_t equals = field.find('=');
      if (equals == std::string_view::npos) {
        file.Fail(offset, "record header field without '=' (not a ROS 1 bag record)");
      }
      fields_.emplace_back(field.substr(0, equals), field.substr(equals + 1));
    }
    file_ = &file;
    offset_ = offset;
  }
  bool Has(std::string_view name) const { return Find(name) != nullptr; }
  std::string_view Bytes(std::string_view name) const {
    const std::string_view* value = Find(name);
    if (value == nullptr) {
      file_->Fail(offset_, "record header has no '" + std::string(name) + "' field");
    }
    return *value;
  }
  template <typename T>
  T Get(std::string_view name) const {
    const std::string_view bytes = Bytes(name);
    if (bytes.size() != sizeof(T)) {
      file_->Fail(offset_, StringPrintf("record header field '%s' has %zu bytes, expected %zu",
                                        std::string(name).c_str(), bytes.size(), sizeof(T)));
    }
    T value;
    std::memcpy(&value, bytes.data(), sizeof(T));
    return value;
  }
  uint8_t op() const { return Get<uint8_t>("op"); }
  // ROS time: uint32 seconds then uint32 nanoseconds.
  int64_t TimeNs(std::string_view name) const {
    const uint64_t packed = Get<uint64_t>(name);
    return static_cast<int64_t>(packed & 0xFFFFFFFFu) * 1'000'000'000 +
           static_cast<int64_t>(packed >> 32);
  }

 private:
  const std::string_view* Find(std::string_view name) const {
    for (const auto& [key, value] : fields_) {
      if (key == name) return &value;
    }
    return nullptr;
  }
  std::vector<std::pair<std::string_view, std::string_view>> fields_;
  const BagFile* file_ = nullptr;
  int64_t offset_ = 0;
};

// A record in the file, its header read.
struct FileRecord {
  std::string header_bytes;
  int64_t offset = 0;
  int64_t data_offset = 0;
  int64_t data_bytes = 0;
  int64_t end() const { return data_offset + data_bytes; }
};

FileRecord ReadFileRecord(const BagFile& file, int64_t offset) {
  FileRecord record;
  record.offset = offset;
  std::string buffer;
  file.Read(offset, 4, "record header length", &buffer);
  int32_t header_bytes;
  std::memcpy(&header_bytes, buffer.data(), 4);
  if (header_bytes < 0 || header_bytes > kMaxHeaderBytes) {
    file.Fail(offset, StringPrintf("record header length %d is not plausible (corrupt bag)",
                                   header_bytes));
  }
  file.Read(offset + 4, header_bytes, "record header", &record.header_bytes);
  file.Read(offset + 4 + header_bytes, 4, "record data length", &buffer);
  int32_t data_bytes;
  std::memcpy(&data_bytes, buffer.data(), 4);
  if (data_bytes < 0) file.Fail(offset, "negative record data length (corrupt bag)");
  record.data_offset = offset + 8 + header_bytes;
  record.data_bytes = data_bytes;
  if (record.end() > file.size()) {
    file.Fail(offset, StringPrintf("record of %d data bytes ends past the end of the file (%lld "
                                   "bytes): truncated?",
                                   data_bytes, static_cast<long long>(file.size())));
  }
  return record;
}

enum class Compression { kNone, kBz2, kLz4 };

struct ChunkLocation {
  uint32_t file = 0;
  int64_t data_offset = 0;  // of the compressed bytes in the file
  int64_t data_bytes = 0;
  uint64_t size = 0;        // decompressed
  Compression compression = Compression::kNone;
};

class Ros1BagReader : public IndexedBagReader {
 public:
  explicit Ros1BagReader(const std::vector<std::string>& paths) {
    for (const std::string& path : paths) {
      files_.push_back(std::make_unique<BagFile>(path));
      Index(static_cast<uint32_t>(files_.size() - 1));
    }
    FinishIndex();
  }
  std::string format() const override { return "ROS 1 bag 2.0"; }

 protected:
  void LoadChunk(uint64_t chunk, std::string* out) override {
    const ChunkLocation& at = chunks_[chunk];
    const BagFile& file = *files_[at.file];
    if (at.compression == Compression::kNone) {
      file.Read(at.data_offset, at.data_bytes, "chunk", out);
      if (static_cast<uint64_t>(at.data_bytes) != at.size) {
        file.Fail(at.data_offset,
                  StringPrintf("uncompressed chunk has %lld bytes, its header says %llu",
                               static_cast<long long>(at.data_bytes),
                               static_cast<unsigned long long>(at.size)));
      }
      return;
    }
    file.Read(at.data_offset, at.data_bytes, "chunk", &compressed_);
    if (at.compression == Compression::kBz2) {
      DecompressBz2(compressed_, at.size, file, at.data_offset, out);
    } else {
      DecompressLz4Frame(compressed_, at.size, file, at.data_offset, out);
    }
  }

  std::string_view MessageAt(const MessageRef& ref, std::string_view chunk, std::string* scratch,
                             std::string* where) override {
    const ChunkLocation& at = chunks_[ref.chunk];
    const BagFile& file = *files_[at.file];
    *where = StringPrintf("%s: chunk at offset %lld, message at %llu", file.path().c_str(),
                          static_cast<long long>(at.data_offset),
                          static_cast<unsigned long long>(ref.offset));
    ByteCursor cursor(chunk, file, at.data_offset);
    if (ref.offset > chunk.size()) {
      file.Fail(at.data_offset, StringPrintf("index points at offset %llu past the chunk's %zu "
                                             "bytes (corrupt index)",
                                             static_cast<unsigned long long>(ref.offset),
                                             chunk.size()));
    }
    cursor.set_pos(ref.offset);
    const uint32_t header_bytes = cursor.Get<uint32_t>("message header length");
    const RecordHeader header(cursor.Bytes(header_bytes, "message header"), file,
                              at.data_offset);
    if (header.op() != kMessageData) {
      file.Fail(at.data_offset, "index points at a record that is not a message (corrupt index)");
    }
    const uint32_t data_bytes = cursor.Get<uint32_t>("message length");
    return cursor.Bytes(data_bytes, "message");
  }

 private:
  void Index(uint32_t file_index) {
    const BagFile& file = *files_[file_index];
    std::string magic;
    if (file.size() < static_cast<int64_t>(kMagic.size())) {
      file.Fail(0, "too short for a ROS 1 bag");
    }
    file.Read(0, kMagic.size(), "magic", &magic);
    if (magic != kMagic) file.Fail(0, "not a ROS 1 bag 2.0 (no '#ROSBAG V2.0' line)");
    const FileRecord bag_header = ReadFileRecord(file, kMagic.size());
    const RecordHeader header(bag_header.header_bytes, file, bag_header.offset);
    if (header.op() != kBagHeader) file.Fail(bag_header.offset, "first record is no bag header");
    const uint64_t index_pos = header.Get<uint64_t>("index_pos");
    if (index_pos == 0 || index_pos >= static_cast<uint64_t>(file.size()) ||
        index_pos < static_cast<uint64_t>(bag_header.end())) {
      warnings_.push_back(file.path() +
                          ": the bag has no index (it was not closed: a recording cut short?); "
                          "read by a linear scan");
      Scan(file_index, bag_header.end());
    } else {
      ReadIndex(file_index, static_cast<int64_t>(index_pos));
    }
  }

  // The topic index of connection `id` of file `file_index` (created on first sight).
  void AddConnection(uint32_t file_index, const RecordHeader& header, std::string_view data,
                     int64_t offset) {
    const BagFile& file = *files_[file_index];
    const uint32_t id = header.Get<uint32_t>("conn");
    const std::string topic_name(header.Bytes("topic"));
    const RecordHeader connection(data, file, offset);
    const std::string type(connection.Bytes("type"));
    const auto key = std::make_pair(file_index, id);
    if (connections_.count(key) > 0) return;  // the index section repeats the chunks' records
    int topic = FindTopic(topic_name);
    if (topic < 0) {
      topics_.push_back({topic_name, type, BagSerialization::kRos1});
      topic = static_cast<int>(topics_.size() - 1);
    } else if (topics_[topic].type != type) {
      file.Fail(offset, "topic " + topic_name + " has type " + type + " here and " +
                            topics_[topic].type + " before");
    }
    connections_[key] = topic;
  }

  int Topic(uint32_t file_index, uint32_t connection, int64_t offset) const {
    const auto found = connections_.find({file_index, connection});
    if (found == connections_.end()) {
      files_[file_index]->Fail(offset, StringPrintf("message of connection %u, which no "
                                                    "connection record defines",
                                                    connection));
    }
    return found->second;
  }

  ChunkLocation ChunkAt(uint32_t file_index, const FileRecord& record,
                        const RecordHeader& header) {
    ChunkLocation at;
    at.file = file_index;
    at.data_offset = record.data_offset;
    at.data_bytes = record.data_bytes;
    at.size = header.Get<uint32_t>("size");
    const std::string_view compression = header.Bytes("compression");
    if (compression == "none") {
      at.compression = Compression::kNone;
    } else if (compression == "bz2") {
      at.compression = Compression::kBz2;
    } else if (compression == "lz4") {
      at.compression = Compression::kLz4;
    } else {
      files_[file_index]->Fail(record.offset, "chunk compression '" + std::string(compression) +
                                                  "' is not one of none, bz2, lz4");
    }
    return at;
  }

  // A closed bag: connections and chunk infos at index_pos, then each chunk's index records.
  void ReadIndex(uint32_t file_index, int64_t index_pos) {
    const BagFile& file = *files_[file_index];
    std::vector<uint64_t> chunk_positions;
    std::string data;
    for (int64_t pos = index_pos; pos < file.size();) {
      const FileRecord record = ReadFileRecord(file, pos);
      const RecordHeader header(record.header_bytes, file, pos);
      if (header.op() == kConnection) {
        file.Read(record.data_offset, record.data_bytes, "connection", &data);
        AddConnection(file_index, header, data, pos);
      } else if (header.op() == kChunkInfo) {
        chunk_positions.push_back(header.Get<uint64_t>("chunk_pos"));
      }
      pos = record.end();
    }
    for (const uint64_t chunk_pos : chunk_positions) {
      if (chunk_pos >= static_cast<uint64_t>(index_pos)) {
        file.Fail(index_pos, "chunk info points past the data section (corrupt index)");
      }
      const FileRecord chunk = ReadFileRecord(file, static_cast<int64_t>(chunk_pos));
      const RecordHeader header(chunk.header_bytes, file, chunk.offset);
      if (header.op() != kChunk) file.Fail(chunk.offset, "chunk info points at no chunk");
      chunks_.push_back(ChunkAt(file_index, chunk, header));
      const uint64_t chunk_index = chunks_.size() - 1;
      for (int64_t pos = chunk.end(); pos < index_pos;) {
        const FileRecord record = ReadFileRecord(file, pos);
        const RecordHeader index(record.header_bytes, file, pos);
        if (index.op() != kIndexData) break;
        const int topic = Topic(file_index, index.Get<uint32_t>("conn"), pos);
        const uint32_t count = index.Get<uint32_t>("count");
        if (static_cast<int64_t>(count) * 12 != record.data_bytes) {
          file.Fail(pos, "index record's count does not match its size (corrupt index)");
        }
        file.Read(record.data_offset, record.data_bytes, "index entries", &data);
        ByteCursor cursor(data, file, record.data_offset);
        for (uint32_t i = 0; i < count; ++i) {
          MessageRef ref;
          const uint32_t sec = cursor.Get<uint32_t>("index time");
          const uint32_t nsec = cursor.Get<uint32_t>("index time");
          ref.time_ns = int64_t{sec} * 1'000'000'000 + nsec;
          ref.offset = cursor.Get<uint32_t>("index offset");
          ref.chunk = chunk_index;
          ref.file = file_index;
          ref.topic = topic;
          refs_.push_back(ref);
        }
        pos = record.end();
      }
    }
  }

  // An unindexed bag: every record in file order, each chunk decompressed to list its messages.
  void Scan(uint32_t file_index, int64_t start) {
    const BagFile& file = *files_[file_index];
    std::string data;
    std::string chunk;
    for (int64_t pos = start; pos < file.size();) {
      const FileRecord record = ReadFileRecord(file, pos);
      const RecordHeader header(record.header_bytes, file, pos);
      if (header.op() == kConnection) {
        file.Read(record.data_offset, record.data_bytes, "connection", &data);
        AddConnection(file_index, header, data, pos);
      } else if (header.op() == kChunk) {
        chunks_.push_back(ChunkAt(file_index, record, header));
        LoadChunk(chunks_.size() - 1, &chunk);
        ScanChunk(file_index, chunks_.size() - 1, chunk);
      }
      pos = record.end();
    }
  }

  void ScanChunk(uint32_t file_index, uint64_t chunk_index, const std::string& chunk) {
    const BagFile& file = *files_[file_index];
    const int64_t base = chunks_[chunk_index].data_offset;
    ByteCursor cursor(chunk, file, base);
    while (cursor.remaining() > 0) {
      const size_t record_pos = cursor.pos();
      const uint32_t header_bytes = cursor.Get<uint32_t>("record header length");
      const RecordHeader header(cursor.Bytes(header_bytes, "record header"), file, base);
      const uint32_t data_bytes = cursor.Get<uint32_t>("record data length");
      const std::string_view data = cursor.Bytes(data_bytes, "record data");
      if (header.op() == kConnection) {
        AddConnection(file_index, header, data, base);
      } else if (header.op() == kMessageData) {
        MessageRef ref;
        ref.time_ns = header.TimeNs("time");
        ref.offset = record_pos;
        ref.chunk = chunk_index;
        ref.file = file_index;
        ref.topic = Topic(file_index, header.Get<uint32_t>("conn"), base);
        refs_.push_back(ref);
      }
    }
  }

  std::vector<ChunkLocation> chunks_;
  std::map<std::pair<uint32_t, uint32_t>, int> connections_;
  std::string compressed_;
};

}  // namespace

std::unique_ptr<BagReader> OpenRos1Bags(const std::vector<std::string>& paths) {
  return std::make_unique<Ros1BagReader>(paths);
}

}  // namespace internal
}  // namespace splinecal
