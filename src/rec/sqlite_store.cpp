// A ROS 2 sqlite3 bag (.db3, rosbag2's default up to Humble): a table of
// topics (name, type, serialization) and a table of messages (topic, time,
// CDR bytes). Opened immutable: reading never writes a journal beside it.
// A bag the recorder did not close holds its last messages (or all of them)
// in FILE-wal: it is read with that log, still without writing a byte.
#include <sqlite3.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <mutex>

#include "core/input_file.hpp"
#include "hba/core/error.hpp"
#include "message_store.hpp"

namespace hba::rec {
namespace fs = std::filesystem;

namespace {

class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql, const fs::path& path) : db_(db), path_(path) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement_, nullptr) != SQLITE_OK) {
      failAt(path, "not a ROS 2 sqlite3 bag (" + std::string(sqlite3_errmsg(db)) + ")");
    }
  }
  ~Statement() { sqlite3_finalize(statement_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  sqlite3_stmt* get() const { return statement_; }
  // True for a row, false at the end; a damaged file is an error, not an end.
  bool step() const {
    const int status = sqlite3_step(statement_);
    if (status == SQLITE_ROW) return true;
    if (status == SQLITE_DONE) return false;
    failAt(path_, "cannot read the bag (" + std::string(sqlite3_errmsg(db_)) + ")");
  }

 private:
  sqlite3* db_ = nullptr;
  fs::path path_;
  sqlite3_stmt* statement_ = nullptr;
};

std::string text(sqlite3_stmt* statement, int column) {
  const unsigned char* value = sqlite3_column_text(statement, column);
  return value ? reinterpret_cast<const char*>(value) : "";
}

// A path inside a "file:" URI: '%', '?' and '#' would end or escape it.
std::string uriPath(const std::string& path) {
  std::string out;
  for (const char c : path) {
    if (c == '%' || c == '?' || c == '#') {
      constexpr const char* kHex = "0123456789ABCDEF";
      out += '%';
      out += kHex[(static_cast<unsigned char>(c) >> 4) & 0xF];
      out += kHex[static_cast<unsigned char>(c) & 0xF];
    } else {
      out += c;
    }
  }
  return out;
}

// The URI that opens the bag without writing a byte beside it. Immutable
// when no write-ahead log holds data (sqlite then ignores any log). A bag
// whose recorder did not close it keeps messages in FILE-wal, indexed by
// FILE-shm: both are read as they are (readonly_shm). Without FILE-shm,
// sqlite reads the log only after creating one, which is refused.
std::string readOnlyUri(const fs::path& path) {
  const std::string uri = "file:" + uriPath(fs::absolute(path).string());
  const fs::path wal = path.string() + "-wal", shm = path.string() + "-shm";
  std::error_code ec;
  if (!regularFileIsPresent(wal) || fs::file_size(wal, ec) == 0) return uri + "?immutable=1";
  if (!regularFileIsPresent(shm)) {
    const std::string name = path.filename().string();
    failAt(path, "the bag is still in WAL mode: " + name + "-wal holds messages not yet in " + name +
                     " (the recorder did not close it), and without " + name +
                     "-shm they cannot be read without writing beside the bag. Copy the folder and run "
                     "`sqlite3 COPY/" +
                     name + " 'PRAGMA wal_checkpoint'` on the copy, then read the copy");
  }
  return uri + "?mode=ro&readonly_shm=1";
}

class SqliteStore : public MessageStore {
 public:
  explicit SqliteStore(const fs::path& path) : path_(path) {
    const std::string uri = readOnlyUri(path);
    if (sqlite3_open_v2(uri.c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr) != SQLITE_OK) {
      const std::string problem = db_ ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      failAt(path, "cannot open as sqlite3 (" + problem + ")");
    }
    try {
      readTopics();
    } catch (...) {
      sqlite3_close(db_);
      throw;
    }
  }
  ~SqliteStore() override { sqlite3_close(db_); }

  const fs::path& path() const override { return path_; }
  std::string format() const override { return "ROS 2 sqlite3 bag"; }
  Serialization serialization() const override { return Serialization::Cdr; }
  const std::vector<StoredChannel>& channels() const override { return channels_; }

  std::vector<StoredMessage> messages(const std::string& topic) const override {
    std::vector<StoredMessage> out;
    const auto channel = std::find_if(channels_.begin(), channels_.end(),
                                      [&topic](const StoredChannel& c) { return c.topic == topic; });
    if (channel == channels_.end()) return out;
    const std::lock_guard<std::mutex> lock(mutex_);
    const Statement query(db_, "SELECT id, timestamp FROM messages WHERE topic_id = ? ORDER BY timestamp",
                          path_);
    sqlite3_bind_int64(query.get(), 1, channel->id);
    while (query.step()) {
      StoredMessage message;
      message.offset = static_cast<std::uint64_t>(sqlite3_column_int64(query.get(), 0));
      message.channel = channel->id;
      message.time = static_cast<double>(sqlite3_column_int64(query.get(), 1)) * 1e-9;
      out.push_back(message);
    }
    return out;
  }

  std::vector<std::uint8_t> read(const StoredMessage& message) const override {
    const std::lock_guard<std::mutex> lock(mutex_);
    const Statement query(db_, "SELECT data FROM messages WHERE id = ?", path_);
    sqlite3_bind_int64(query.get(), 1, static_cast<sqlite3_int64>(message.offset));
    if (!query.step()) failAt(path_, "message " + std::to_string(message.offset) + " is gone");
    const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(query.get(), 0));
    const int size = sqlite3_column_bytes(query.get(), 0);
    return std::vector<std::uint8_t>(data, data + size);
  }

 private:
  void readTopics() {
    std::map<std::uint32_t, std::size_t> counts;
    {
      const Statement query(db_, "SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id", path_);
      while (query.step()) {
        counts[static_cast<std::uint32_t>(sqlite3_column_int64(query.get(), 0))] =
            static_cast<std::size_t>(sqlite3_column_int64(query.get(), 1));
      }
    }
    const Statement query(db_, "SELECT id, name, type, serialization_format FROM topics ORDER BY id", path_);
    while (query.step()) {
      StoredChannel channel;
      channel.id = static_cast<std::uint32_t>(sqlite3_column_int64(query.get(), 0));
      channel.topic = text(query.get(), 1);
      const std::string format = text(query.get(), 3);
      channel.type = format == "cdr" ? rosTypeName(text(query.get(), 2))
                                     : text(query.get(), 2) + " (" + format + ", not read)";
      channel.messages = counts[channel.id];
      channels_.push_back(channel);
    }
  }

  fs::path path_;
  sqlite3* db_ = nullptr;
  mutable std::mutex mutex_;
  std::vector<StoredChannel> channels_;
};

}  // namespace

bool looksLikeSqlite(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char start[16] = {};
  in.read(start, 16);
  return in && std::string(start, 16) == std::string("SQLite format 3\0", 16);
}

std::unique_ptr<MessageStore> openSqlite(const fs::path& path) { return std::make_unique<SqliteStore>(path); }

}  // namespace hba::rec
