// rosbag2's sqlite3 storage: a table `topics` (id, name, type, serialization_format, ...) and a
// table `messages` (id, topic_id, timestamp [ns], data), one database per file of the recording.
// The message list (rowid, time, topic) is read once and sorted by time; each message's data is
// then read by its rowid, so that the blobs are never sorted or loaded together.
#include <sqlite3.h>

#include <algorithm>
#include <map>

#include "bag_formats.h"
#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace internal {
namespace {

struct SqliteRef {
  int64_t time_ns = 0;
  int64_t rowid = 0;
  uint32_t file = 0;
  int32_t topic = 0;
};

class Database {
 public:
  explicit Database(const std::string& path) : path_(path) {
    if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
      const std::string message = db_ != nullptr ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      db_ = nullptr;
      throw Error(path, 0, "cannot open as a rosbag2 sqlite3 database: " + message);
    }
  }
  ~Database() {
    sqlite3_finalize(data_);
    sqlite3_close(db_);
  }
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  const std::string& path() const { return path_; }

  // A statement; throws naming the file when the schema is not rosbag2's.
  sqlite3_stmt* Prepare(const char* sql) {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(db_, sql, -1, &statement, nullptr) != SQLITE_OK) {
      throw Error(path_, 0, std::string("not a rosbag2 sqlite3 database (") + sqlite3_errmsg(db_) +
                                ")");
    }
    return statement;
  }
  // Steps; true for a row, false at the end, throws on an error.
  bool Step(sqlite3_stmt* statement) {
    const int status = sqlite3_step(statement);
    if (status == SQLITE_ROW) return true;
    if (status == SQLITE_DONE) return false;
    throw Error(path_, 0, std::string("sqlite3: ") + sqlite3_errmsg(db_));
  }
  // The data of message `rowid`, copied into `out`.
  void Data(int64_t rowid, std::string* out) {
    if (data_ == nullptr) data_ = Prepare("SELECT data FROM messages WHERE id = ?");
    sqlite3_reset(data_);
    sqlite3_bind_int64(data_, 1, rowid);
    if (!Step(data_)) throw Error(path_, 0, StringPrintf("message %lld vanished", (long long)rowid));
    const void* blob = sqlite3_column_blob(data_, 0);
    const int bytes = sqlite3_column_bytes(data_, 0);
    out->assign(static_cast<const char*>(blob), static_cast<size_t>(bytes));
  }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* data_ = nullptr;
};

// Finalizes a statement at the end of a scope.
struct Statement {
  sqlite3_stmt* statement;
  ~Statement() { sqlite3_finalize(statement); }
};

class SqliteBagReader : public BagReader {
 public:
  explicit SqliteBagReader(const std::vector<std::string>& paths) {
    for (const std::string& path : paths) {
      if (FILE* probe = std::fopen(path.c_str(), "rb")) {
        std::fclose(probe);
      } else {
        throw Error(path, 0, "missing or unreadable .db3 file of the recording");
      }
      databases_.push_back(std::make_unique<Database>(path));
      Index(static_cast<uint32_t>(databases_.size() - 1));
    }
    std::stable_sort(refs_.begin(), refs_.end(),
                     [](const SqliteRef& a, const SqliteRef& b) { return a.time_ns < b.time_ns; });
    for (const SqliteRef& ref : refs_) AddTopicStatistics(ref.topic, ref.time_ns, &topics_);
    selected_.assign(topics_.size(), true);
  }
  std::string format() const override { return "ROS 2 sqlite3"; }

  void SelectTopics(const std::vector<int>& topics) override {
    selected_.assign(topics_.size(), false);
    for (const int topic : topics) selected_.at(topic) = true;
    next_ = 0;
  }

  bool Next(BagMessage* message) override {
    while (next_ < refs_.size() && !selected_[refs_[next_].topic]) ++next_;
    if (next_ == refs_.size()) return false;
    const SqliteRef& ref = refs_[next_++];
    Database& database = *databases_[ref.file];
    database.Data(ref.rowid, &data_);
    message->topic = ref.topic;
    message->receive_time_ns = ref.time_ns;
    message->data = data_;
    message->where = StringPrintf("%s: message id %lld", database.path().c_str(),
                                  static_cast<long long>(ref.rowid));
    return true;
  }

 private:
  void Index(uint32_t file) {
    Database& database = *databases_[file];
    std::map<int64_t, int> topic_of_id;
    {
      Statement topics{database.Prepare("SELECT id, name, type, serialization_format FROM topics")};
      while (database.Step(topics.statement)) {
        const auto text = [&](int column) {
          const unsigned char* value = sqlite3_column_text(topics.statement, column);
          return value == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(value));
        };
        const std::string name = text(1);
        const std::string type = text(2);
        const std::string serialization = text(3);
        if (serialization != "cdr") {
          throw Error(database.path(), 0, "topic " + name + " is serialized as '" +
                                              serialization + "', splinecal reads 'cdr'");
        }
        int topic = FindTopic(name);
        if (topic < 0) {
          topics_.push_back({name, type, BagSerialization::kCdr});
          topic = static_cast<int>(topics_.size() - 1);
        } else if (topics_[topic].type != type) {
          throw Error(database.path(), 0, "topic " + name + " has type " + type + " here and " +
                                              topics_[topic].type + " before");
        }
        topic_of_id[sqlite3_column_int64(topics.statement, 0)] = topic;
      }
    }
    Statement messages{database.Prepare("SELECT id, timestamp, topic_id FROM messages")};
    while (database.Step(messages.statement)) {
      SqliteRef ref;
      ref.rowid = sqlite3_column_int64(messages.statement, 0);
      ref.time_ns = sqlite3_column_int64(messages.statement, 1);
      ref.file = file;
      const auto found = topic_of_id.find(sqlite3_column_int64(messages.statement, 2));
      if (found == topic_of_id.end()) {
        throw Error(database.path(), 0, StringPrintf("message id %lld has a topic_id no topic has",
                                                     static_cast<long long>(ref.rowid)));
      }
      ref.topic = found->second;
      refs_.push_back(ref);
    }
    FILE* file_handle = std::fopen(database.path().c_str(), "rb");
    if (file_handle != nullptr) {
      std::fseek(file_handle, 0, SEEK_END);
      file_bytes_ += std::ftell(file_handle);
      std::fclose(file_handle);
    }
  }

  std::vector<std::unique_ptr<Database>> databases_;
  std::vector<SqliteRef> refs_;
  std::vector<bool> selected_;
  size_t next_ = 0;
  std::string data_;
};

}  // namespace

std::unique_ptr<BagReader> OpenRosbag2Sqlite(const std::vector<std::string>& db3_paths) {
  return std::make_unique<SqliteBagReader>(db3_paths);
}

}  // namespace internal
}  // namespace splinecal
