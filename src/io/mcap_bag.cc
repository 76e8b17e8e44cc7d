// MCAP (mcap.dev/spec, version 0): records of an opcode, a uint64 length and fields, between two
// magic strings. Messages (op 0x05) sit in the data section, mostly inside chunks (op 0x06,
// compressed "", "zstd" or "lz4", with a CRC-32 of the decompressed records); the summary section
// at the end (pointed at by the footer) repeats the schemas and channels and holds a chunk index
// (op 0x08) per chunk, whose message index records (op 0x07, right after each chunk) give every
// message's log time and offset in the decompressed chunk. A file without a summary (a writer
// that did not finish) is read by a linear scan.
#include <map>

#include "bag_formats.h"
#include "indexed_bag_reader.h"
#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace internal {
namespace {

constexpr std::string_view kMagic("\x89MCAP0\r\n", 8);
enum Op : uint8_t {
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kDataEnd = 0x0F,
};
constexpr int64_t kFooterRecordBytes = 1 + 8 + 8 + 8 + 4;
// Schema, channel and index records larger than this are corrupt (a chunk or a message is not
// read whole through this path).
constexpr uint64_t kMaxSmallRecordBytes = uint64_t{1} << 28;

std::string_view String(ByteCursor* cursor, const char* what) {
  return cursor->Bytes(cursor->Get<uint32_t>(what), what);
}

enum class Compression { kNone, kZstd, kLz4 };

struct ChunkLocation {
  int64_t records_offset = 0;  // of the (compressed) records in the file
  uint64_t records_bytes = 0;
  uint64_t size = 0;  // decompressed
  uint32_t crc = 0;   // of the decompressed records; 0: not computed by the writer
  Compression compression = Compression::kNone;
};

class McapReader : public IndexedBagReader {
 public:
  explicit McapReader(const std::string& path) {
    files_.push_back(std::make_unique<BagFile>(path));
    const BagFile& file = *files_[0];
    std::string bytes;
    if (file.size() < static_cast<int64_t>(kMagic.size())) file.Fail(0, "too short for MCAP");
    file.Read(0, kMagic.size(), "magic", &bytes);
    if (bytes != kMagic) file.Fail(0, "not an MCAP file (no MCAP magic)");
    const Summary summary = ReadSummary();
    if (summary != Summary::kIndexed) {
      if (summary == Summary::kMissing) {
        warnings_.push_back(path + ": no MCAP summary with message indexes (a writer that did not "
                                   "finish?); read by a linear scan");
      }
      topics_.clear();
      channels_.clear();
      schemas_.clear();
      chunks_.clear();
      refs_.clear();
      Scan();
    }
    FinishIndex();
  }
  std::string format() const override { return "MCAP"; }

 protected:
  void LoadChunk(uint64_t chunk, std::string* out) override {
    const ChunkLocation& at = chunks_[chunk];
    const BagFile& file = *files_[0];
    if (at.compression == Compression::kNone) {
      file.Read(at.records_offset, at.records_bytes, "chunk", out);
      if (at.records_bytes != at.size) {
        file.Fail(at.records_offset, "uncompressed chunk's size differs from its header's");
      }
    } else {
      file.Read(at.records_offset, at.records_bytes, "chunk", &compressed_);
      if (at.compression == Compression::kZstd) {
        DecompressZstd(compressed_, at.size, file, at.records_offset, out);
      } else {
        DecompressLz4Frame(compressed_, at.size, file, at.records_offset, out);
      }
    }
    if (at.crc != 0 && Crc32(*out) != at.crc) {
      file.Fail(at.records_offset,
                StringPrintf("chunk fails its CRC (computed %08x, recorded %08x): corrupt chunk",
                             Crc32(*out), at.crc));
    }
  }

  std::string_view MessageAt(const MessageRef& ref, std::string_view chunk, std::string* scratch,
                             std::string* where) override {
    const BagFile& file = *files_[0];
    std::string_view record;
    int64_t base;
    if (ref.chunk == kNoChunk) {
      base = static_cast<int64_t>(ref.offset);
      *where = StringPrintf("%s: message at offset %lld", file.path().c_str(),
                            static_cast<long long>(base));
      const uint64_t length = RecordLength(static_cast<int64_t>(ref.offset));
      file.Read(static_cast<int64_t>(ref.offset) + 9, static_cast<int64_t>(length), "message",
                scratch);
      record = *scratch;
    } else {
      base = chunks_[ref.chunk].records_offset;
      *where = StringPrintf("%s: chunk at offset %lld, message at %llu", file.path().c_str(),
                            static_cast<long long>(base),
                            static_cast<unsigned long long>(ref.offset));
      ByteCursor cursor(chunk, file, base);
      if (ref.offset > chunk.size()) cursor.Fail("message index points past its chunk");
      cursor.set_pos(ref.offset);
      if (cursor.Get<uint8_t>("opcode") != kMessage) {
        cursor.Fail("message index points at a record that is not a message (corrupt index)");
      }
      record = cursor.Bytes(cursor.Get<uint64_t>("record length"), "message record");
    }
    ByteCursor cursor(record, file, base);
    cursor.Bytes(2 + 4 + 8 + 8, "message header");  // channel, sequence, log and publish time
    return record.substr(cursor.pos());
  }

 private:
  uint64_t RecordLength(int64_t offset) {
    std::string bytes;
    files_[0]->Read(offset + 1, 8, "record length", &bytes);
    uint64_t length;
    std::memcpy(&length, bytes.data(), 8);
    return length;
  }

  // Reads record at `offset` whole (opcode, content); returns its end.
  int64_t ReadRecord(int64_t offset, uint8_t* op, std::string* content) {
    const BagFile& file = *files_[0];
    std::string head;
    file.Read(offset, 9, "record", &head);
    *op = static_cast<uint8_t>(head[0]);
    uint64_t length;
    std::memcpy(&length, head.data() + 1, 8);
    if (length > static_cast<uint64_t>(file.size())) {
      file.Fail(offset, StringPrintf("record length %llu exceeds the file (corrupt or truncated)",
                                     static_cast<unsigned long long>(length)));
    }
    if (*op != kChunk && *op != kMessage && length > kMaxSmallRecordBytes) {
      file.Fail(offset, "record length is not plausible (corrupt file)");
    }
    file.Read(offset + 9, static_cast<int64_t>(length), "record", content);
    return offset + 9 + static_cast<int64_t>(length);
  }

  void AddSchema(std::string_view content, int64_t offset) {
    ByteCursor cursor(content, *files_[0], offset);
    const uint16_t id = cursor.Get<uint16_t>("schema id");
    schemas_[id] = std::string(String(&cursor, "schema name"));
  }

  void AddChannel(std::string_view content, int64_t offset) {
    const BagFile& file = *files_[0];
    ByteCursor cursor(content, file, offset);
    const uint16_t id = cursor.Get<uint16_t>("channel id");
    const uint16_t schema = cursor.Get<uint16_t>("channel schema id");
    const std::string topic_name(String(&cursor, "channel topic"));
    const std::string encoding(String(&cursor, "channel message encoding"));
    if (channels_.count(id) > 0) return;
    const auto found = schemas_.find(schema);
    const std::string type = found == schemas_.end() ? "" : found->second;
    BagSerialization serialization;
    if (encoding == "cdr") {
      serialization = BagSerialization::kCdr;
    } else if (encoding == "ros1") {
      serialization = BagSerialization::kRos1;
    } else {
      // Listed, never parsed: io/bag_messages.h refuses it by type.
      serialization = BagSerialization::kCdr;
    }
    int topic = FindTopic(topic_name);
    if (topic < 0) {
      topics_.push_back({topic_name, type, serialization});
      topic = static_cast<int>(topics_.size() - 1);
    } else if (topics_[topic].type != type) {
      file.Fail(offset, "topic " + topic_name + " has two channels of types " + type + " and " +
                            topics_[topic].type);
    }
    channels_[id] = topic;
  }

  int Topic(uint16_t channel, int64_t offset) const {
    const auto found = channels_.find(channel);
    if (found == channels_.end()) {
      files_[0]->Fail(offset, StringPrintf("message of channel %u, which no channel record "
                                           "defines",
                                           channel));
    }
    return found->second;
  }

  ChunkLocation ChunkFromRecord(std::string_view content, int64_t offset) {
    // The chunk's fields, then its records; `offset` is where the content starts.
    ByteCursor cursor(content, *files_[0], offset);
    cursor.Get<uint64_t>("chunk start time");
    cursor.Get<uint64_t>("chunk end time");
    ChunkLocation at;
    at.size = cursor.Get<uint64_t>("chunk uncompressed size");
    at.crc = cursor.Get<uint32_t>("chunk CRC");
    at.compression = ParseCompression(String(&cursor, "chunk compression"), offset);
    at.records_bytes = cursor.Get<uint64_t>("chunk records length");
    at.records_offset = cursor.offset();
    if (at.records_bytes > cursor.remaining()) {
      cursor.Fail("chunk records run past the chunk record (wrong chunk size or truncated)");
    }
    return at;
  }

  Compression ParseCompression(std::string_view name, int64_t offset) const {
    if (name.empty()) return Compression::kNone;
    if (name == "zstd") return Compression::kZstd;
    if (name == "lz4") return Compression::kLz4;
    files_[0]->Fail(offset, "chunk compression '" + std::string(name) +
                                "' is not one of none, zstd, lz4");
  }

  enum class Summary {
    kIndexed,    // chunk and message indexes of every message read
    kMissing,    // no summary, or a chunk without message indexes
    kUnchunked,  // a summary without chunks: messages outside chunks, which MCAP never indexes
  };
  // The summary section: schemas, channels, chunk indexes, then each chunk's message indexes.
  Summary ReadSummary() {
    const BagFile& file = *files_[0];
    const int64_t footer = file.size() - static_cast<int64_t>(kMagic.size()) - kFooterRecordBytes;
    if (footer < static_cast<int64_t>(kMagic.size())) return Summary::kMissing;
    std::string bytes;
    file.Read(footer, kFooterRecordBytes + kMagic.size(), "footer", &bytes);
    if (bytes.substr(kFooterRecordBytes) != kMagic || bytes[0] != kFooter) {
      return Summary::kMissing;
    }
    ByteCursor cursor(bytes, file, footer);
    cursor.Bytes(9, "footer opcode and length");
    const uint64_t summary_start = cursor.Get<uint64_t>("summary start");
    cursor.Get<uint64_t>("summary offset start");
    const uint32_t summary_crc = cursor.Get<uint32_t>("summary CRC");
    if (summary_start == 0) return Summary::kMissing;
    if (summary_start >= static_cast<uint64_t>(footer)) {
      file.Fail(footer, "footer's summary start is past the footer (corrupt footer)");
    }
    std::string summary;
    file.Read(static_cast<int64_t>(summary_start),
              footer - static_cast<int64_t>(summary_start), "summary", &summary);
    if (summary_crc != 0 &&
        Crc32(std::string_view(bytes).substr(0, 1 + 8 + 8 + 8), Crc32(summary)) != summary_crc) {
      file.Fail(static_cast<int64_t>(summary_start), "summary section fails its CRC (corrupt)");
    }
    struct Index {
      ChunkLocation chunk;
      int64_t message_index_offset;
      uint64_t message_index_bytes;
    };
    std::vector<Index> indexes;
    ByteCursor records(summary, file, static_cast<int64_t>(summary_start));
    while (records.remaining() > 0) {
      const uint8_t op = records.Get<uint8_t>("opcode");
      const int64_t offset = records.offset();
      const std::string_view content =
          records.Bytes(records.Get<uint64_t>("record length"), "summary record");
      if (op == kSchema) {
        AddSchema(content, offset);
      } else if (op == kChannel) {
        AddChannel(content, offset);
      } else if (op == kChunkIndex) {
        ByteCursor index(content, file, offset + 8);
        index.Get<uint64_t>("chunk start time");
        index.Get<uint64_t>("chunk end time");
        const uint64_t chunk_start = index.Get<uint64_t>("chunk start offset");
        const uint64_t chunk_length = index.Get<uint64_t>("chunk length");
        index.Bytes(index.Get<uint32_t>("message index offsets"), "message index offsets");
        const uint64_t message_index_bytes = index.Get<uint64_t>("message index length");
        if (chunk_start > static_cast<uint64_t>(file.size()) ||
            chunk_length > static_cast<uint64_t>(file.size()) - chunk_start) {
          index.Fail("chunk index points past the end of the file (truncated?)");
        }
        indexes.push_back({ChunkLocation(), static_cast<int64_t>(chunk_start + chunk_length),
                           message_index_bytes});
        std::string chunk_record;
        uint8_t chunk_op;
        // The chunk's fields only (not its records): read its head.
        const int64_t head_bytes = std::min<int64_t>(static_cast<int64_t>(chunk_length), 4096);
        file.Read(static_cast<int64_t>(chunk_start), head_bytes, "chunk", &chunk_record);
        chunk_op = static_cast<uint8_t>(chunk_record[0]);
        if (chunk_op != kChunk) index.Fail("chunk index points at a record that is no chunk");
        uint64_t length;
        std::memcpy(&length, chunk_record.data() + 1, 8);
        if (length + 9 != chunk_length) {
          file.Fail(static_cast<int64_t>(chunk_start),
                    StringPrintf("chunk record is %llu bytes long, its index says %llu (wrong "
                                 "chunk size)",
                                 static_cast<unsigned long long>(length + 9),
                                 static_cast<unsigned long long>(chunk_length)));
        }
        // ChunkFromRecord checks the records against the whole chunk's length: give it a view
        // sized as the record, of which only the head is read.
        std::string content_view = chunk_record.substr(9);
        content_view.resize(length);
        indexes.back().chunk =
            ChunkFromRecord(content_view, static_cast<int64_t>(chunk_start) + 9);
      }
    }
    if (indexes.empty()) return Summary::kUnchunked;
    for (const Index& index : indexes) {
      if (index.message_index_bytes == 0 && index.chunk.size > 0) return Summary::kMissing;
      chunks_.push_back(index.chunk);
      std::string message_indexes;
      file.Read(index.message_index_offset, static_cast<int64_t>(index.message_index_bytes),
                "message indexes", &message_indexes);
      ByteCursor cursor(message_indexes, file, index.message_index_offset);
      while (cursor.remaining() > 0) {
        const uint8_t op = cursor.Get<uint8_t>("opcode");
        const int64_t offset = cursor.offset();
        const std::string_view content =
            cursor.Bytes(cursor.Get<uint64_t>("record length"), "message index record");
        if (op != kMessageIndex) continue;
        ByteCursor entries(content, file, offset + 8);
        const int topic = Topic(entries.Get<uint16_t>("channel id"), offset);
        const uint32_t bytes_of_entries = entries.Get<uint32_t>("message index length");
        if (bytes_of_entries % 16 != 0) entries.Fail("message index length is not 16 n");
        for (uint32_t i = 0; i < bytes_of_entries / 16; ++i) {
          MessageRef ref;
          ref.time_ns = static_cast<int64_t>(entries.Get<uint64_t>("log time"));
          ref.offset = entries.Get<uint64_t>("message offset");
          ref.chunk = chunks_.size() - 1;
          ref.topic = topic;
          refs_.push_back(ref);
        }
      }
    }
    return Summary::kIndexed;
  }

  // Every record of the data section in order; chunks decompressed to list their messages.
  void Scan() {
    const BagFile& file = *files_[0];
    std::string content;
    std::string chunk;
    for (int64_t pos = static_cast<int64_t>(kMagic.size()); pos < file.size();) {
      if (file.size() - pos == static_cast<int64_t>(kMagic.size())) break;  // trailing magic
      uint8_t op;
      int64_t end;
      if (IsLargeRecord(pos, &op)) {
        end = ScanLarge(pos, op, &chunk);
      } else {
        end = ReadRecord(pos, &op, &content);
        if (op == kSchema) AddSchema(content, pos + 9);
        if (op == kChannel) AddChannel(content, pos + 9);
        if (op == kDataEnd || op == kFooter) break;
      }
      pos = end;
    }
  }

  bool IsLargeRecord(int64_t pos, uint8_t* op) {
    std::string head;
    files_[0]->Read(pos, 1, "opcode", &head);
    *op = static_cast<uint8_t>(head[0]);
    return *op == kChunk || *op == kMessage;
  }

  // A chunk or a message outside chunks, found by the scan; returns the record's end.
  int64_t ScanLarge(int64_t pos, uint8_t op, std::string* chunk) {
    const BagFile& file = *files_[0];
    const uint64_t length = RecordLength(pos);
    if (length > static_cast<uint64_t>(file.size() - pos - 9)) {
      file.Fail(pos, "record ends past the end of the file (truncated?)");
    }
    if (op == kMessage) {
      std::string head;
      file.Read(pos + 9, 2 + 4 + 8, "message header", &head);
      ByteCursor cursor(head, file, pos + 9);
      MessageRef ref;
      ref.topic = Topic(cursor.Get<uint16_t>("channel id"), pos);
      cursor.Get<uint32_t>("sequence");
      ref.time_ns = static_cast<int64_t>(cursor.Get<uint64_t>("log time"));
      ref.chunk = kNoChunk;
      ref.offset = static_cast<uint64_t>(pos);
      refs_.push_back(ref);
      return pos + 9 + static_cast<int64_t>(length);
    }
    std::string head;
    const int64_t head_bytes = std::min<int64_t>(static_cast<int64_t>(length), 4096);
    file.Read(pos + 9, head_bytes, "chunk", &head);
    head.resize(length);
    chunks_.push_back(ChunkFromRecord(head, pos + 9));
    LoadChunk(chunks_.size() - 1, chunk);
    const int64_t base = chunks_.back().records_offset;
    ByteCursor cursor(*chunk, file, base);
    while (cursor.remaining() > 0) {
      const size_t record_pos = cursor.pos();
      const uint8_t inner = cursor.Get<uint8_t>("opcode");
      const std::string_view content =
          cursor.Bytes(cursor.Get<uint64_t>("record length"), "chunk record");
      if (inner == kSchema) AddSchema(content, base);
      if (inner == kChannel) AddChannel(content, base);
      if (inner == kMessage) {
        ByteCursor message(content, file, base);
        MessageRef ref;
        ref.topic = Topic(message.Get<uint16_t>("channel id"), base);
        message.Get<uint32_t>("sequence");
        ref.time_ns = static_cast<int64_t>(message.Get<uint64_t>("log time"));
        ref.chunk = chunks_.size() - 1;
        ref.offset = record_pos;
        refs_.push_back(ref);
      }
    }
    return pos + 9 + static_cast<int64_t>(length);
  }

  std::map<uint16_t, std::string> schemas_;
  std::map<uint16_t, int> channels_;
  std::vector<ChunkLocation> chunks_;
  std::string compressed_;
};

}  // namespace

std::unique_ptr<BagReader> OpenMcap(const std::string& path) {
  return std::make_unique<McapReader>(path);
}

}  // namespace internal
}  // namespace splinecal
