/// \file
/// rosbag2 sqlite3 storage (rosbag2_storage_default_plugins, sqlite3 plugin): tables
/// topics(id, name, type, serialization_format, offered_qos_profiles) and
/// messages(id, topic_id, timestamp, data), timestamps in ns. Read through libsqlite3, read-only,
/// messages in (timestamp, id) order as `ros2 bag play` does.

#include <sqlite3.h>

#include <map>

#include "mote/core/error.hpp"
#include "ros2_storage.hpp"

namespace mote::logs::detail {
namespace {

class SqliteStorage final : public Ros2Storage {
 public:
  SqliteStorage(const std::filesystem::path& path, const ReaderOptions& /*options*/)
      : name_(path.string()) {
    if (!std::filesystem::is_regular_file(path)) throw InputError(name_, "", "cannot open file");
    sqlite3* db = nullptr;
    const int rc = sqlite3_open_v2(name_.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
    db_.reset(db);
    if (rc != SQLITE_OK) fail("", "cannot open the sqlite3 database");
    read_topics();
    messages_ = prepare("SELECT topic_id, timestamp, data, id FROM messages ORDER BY timestamp, id",
                        "table messages");
  }

  [[nodiscard]] const std::string& name() const override { return name_; }
  [[nodiscard]] const std::vector<Ros2Topic>& topics() const override { return topics_; }
  [[nodiscard]] const ReadStats& stats() const override { return stats_; }
  [[nodiscard]] StorageSummary summary() const override { return {"sqlite3", "", "sqlite3 query"}; }

  std::optional<Ros2Message> next() override {
    sqlite3_stmt* q = messages_.get();
    const int rc = sqlite3_step(q);
    if (rc == SQLITE_DONE) return std::nullopt;
    const std::string place = "messages row after id " + std::to_string(last_id_);
    if (rc != SQLITE_ROW) fail(place, "cannot read the table");
    last_id_ = sqlite3_column_int64(q, 3);
    Ros2Message m;
    m.place = "messages row id " + std::to_string(last_id_);
    const auto topic = topic_of_.find(sqlite3_column_int64(q, 0));
    if (topic == topic_of_.end()) {
      fail(m.place, "topic_id " + std::to_string(sqlite3_column_int64(q, 0)) +
                        " is not in the topics table");
    }
    if (sqlite3_column_type(q, 2) != SQLITE_BLOB && sqlite3_column_type(q, 2) != SQLITE_NULL) {
      fail(m.place, "data is not a blob");
    }
    m.topic = topic->second;
    m.time_ns = sqlite3_column_int64(q, 1);
    const void* blob = sqlite3_column_blob(q, 2);
    const int bytes = sqlite3_column_bytes(q, 2);
    if (blob != nullptr) m.data = {static_cast<const char*>(blob), static_cast<std::size_t>(bytes)};
    return m;
  }

 private:
  struct CloseDb {
    void operator()(sqlite3* db) const { sqlite3_close(db); }
  };
  struct Finalize {
    void operator()(sqlite3_stmt* q) const { sqlite3_finalize(q); }
  };
  using Statement = std::unique_ptr<sqlite3_stmt, Finalize>;

  [[noreturn]] void fail(const std::string& place, const std::string& problem) const {
    const char* why = db_ ? sqlite3_errmsg(db_.get()) : "out of memory";
    throw InputError(name_, place, problem + " (sqlite3: " + why + ")");
  }

  Statement prepare(const char* sql, const std::string& place) {
    sqlite3_stmt* q = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql, -1, &q, nullptr) != SQLITE_OK) {
      sqlite3_finalize(q);
      fail(place, "not a rosbag2 sqlite3 database");
    }
    return Statement(q);
  }

  static std::string text(sqlite3_stmt* q, int column) {
    const unsigned char* t = sqlite3_column_text(q, column);
    return t == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(t));
  }

  void read_topics() {
    const Statement q = prepare(
        "SELECT id, name, type, serialization_format FROM topics ORDER BY id", "table topics");
    int rc = 0;
    while ((rc = sqlite3_step(q.get())) == SQLITE_ROW) {
      const std::int64_t id = sqlite3_column_int64(q.get(), 0);
      Ros2Topic t{text(q.get(), 1),
                  text(q.get(), 2),
                  text(q.get(), 3),
                  "topics row id " + std::to_string(id),
                  "",
                  ""};
      topic_of_[id] = topics_.size();
      topics_.push_back(std::move(t));
    }
    if (rc != SQLITE_DONE) fail("table topics", "cannot read the table");
  }

  std::string name_;
  std::unique_ptr<sqlite3, CloseDb> db_;
  Statement messages_;
  std::vector<Ros2Topic> topics_;
  std::map<std::int64_t, std::size_t> topic_of_;
  ReadStats stats_;
  std::int64_t last_id_ = 0;
};

}  // namespace

std::unique_ptr<Ros2Storage> open_sqlite_storage(const std::filesystem::path& path,
                                                 const ReaderOptions& options) {
  return std::make_unique<SqliteStorage>(path, options);
}

}  // namespace mote::logs::detail
