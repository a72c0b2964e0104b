// rosbag2's sqlite3 storage: a .db3 file per split, queried for the columns every rosbag2
// version has (topics: id, name, type, serialization_format; messages: id, topic_id, timestamp,
// data). BagMessageView::offset is 0: a row of a database has no byte offset.
#include <sqlite3.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <map>
#include <memory>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/logs/bag_file.hpp"
#include "floorgrid/io/logs/rosbag2_folder.hpp"

namespace floorgrid::io {
namespace {

// A URI that opens `path` read-only as immutable: no journal or WAL file is looked for or made,
// so a bag in a read-only folder opens too.
std::string immutable_uri(const std::string& path) {
  static const char* hex = "0123456789ABCDEF";
  std::string uri = "file:";
  for (const char c : path) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '/' || c == '.' || c == '-' || c == '_' || c == '~') {
      uri += c;
    } else {
      uri += '%';
      uri += hex[u >> 4];
      uri += hex[u & 15];
    }
  }
  return uri + "?immutable=1";
}

class Database {
 public:
  Database(const std::filesystem::path& path, const BagReadLimits& limits) : name_(path.string()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
      throw InputError("no such rosbag2 sqlite3 file", name_);
    sqlite3* raw = nullptr;
    const int status = sqlite3_open_v2(immutable_uri(name_).c_str(), &raw,
                                       SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr);
    db_.reset(raw);
    if (status != SQLITE_OK)
      fail("cannot open");
    // No value read may be larger than a bag's chunk may.
    sqlite3_limit(db_.get(), SQLITE_LIMIT_LENGTH,
                  static_cast<int>(std::min<std::uint64_t>(limits.max_chunk_bytes, INT32_MAX)));
  }

  const std::string& name() const { return name_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(what + ": " + (db_ ? sqlite3_errmsg(db_.get()) : "out of memory") +
                         " (not a rosbag2 sqlite3 file?)",
                     name_);
  }

  // A prepared statement; a missing table or column is an InputError naming the file.
  std::unique_ptr<sqlite3_stmt, int (*)(sqlite3_stmt*)> prepare(const std::string& sql) const {
    sqlite3_stmt* raw = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql.c_str(), -1, &raw, nullptr) != SQLITE_OK)
      fail("cannot query it");
    return {raw, &sqlite3_finalize};
  }

  // Steps `statement`: true for a row, false at the end.
  bool step(sqlite3_stmt* statement) const {
    const int status = sqlite3_step(statement);
    if (status == SQLITE_ROW)
      return true;
    if (status != SQLITE_DONE)
      fail("cannot read it");
    return false;
  }

 private:
  std::string name_;
  std::unique_ptr<sqlite3, int (*)(sqlite3*)> db_{nullptr, &sqlite3_close};
};

std::string column_text(sqlite3_stmt* statement, int column) {
  const unsigned char* text = sqlite3_column_text(statement, column);
  return text != nullptr ? reinterpret_cast<const char*>(text) : "";
}

// Refuses `name` unless it is an ordinary table: a view (a recursive one never ends), a virtual
// table or a generated column computes what it gives, at a cost the file chooses.
void require_table(const Database& db, const std::string& name) {
  const auto query =
      db.prepare("SELECT type, sql FROM sqlite_master WHERE name = '" + name + "' COLLATE NOCASE");
  if (!db.step(query.get()))
    throw InputError("has no " + name + " table (not a rosbag2 sqlite3 file?)", db.name());
  const std::string type = column_text(query.get(), 0);
  std::string sql = column_text(query.get(), 1);
  for (char& c : sql)
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (type != "table" || sql.find("VIRTUAL") != std::string::npos)
    throw InputError("its " + name + " is a " + (type == "table" ? "virtual table" : type) +
                         ", not a table as rosbag2 writes it: refused (it could compute without "
                         "end)",
                     db.name());
  const auto columns = db.prepare("PRAGMA table_xinfo(" + name + ")");
  while (db.step(columns.get())) {
    // hidden: 2 and 3 are generated columns
    if (sqlite3_column_int(columns.get(), 6) >= 2)
      throw InputError("its " + name + " table has a generated column (" +
                           column_text(columns.get(), 1) +
                           "), which rosbag2 never writes: refused (it computes what it gives)",
                       db.name());
  }
}

// The topics table, in id order, and a warning per serialization floorgrid cannot decode.
std::vector<BagTopic> read_topics(const Database& db, std::vector<std::string>& warnings) {
  require_table(db, "topics");
  std::vector<BagTopic> topics;
  const auto query =
      db.prepare("SELECT id, name, type, serialization_format FROM topics ORDER BY id");
  while (db.step(query.get())) {
    BagTopic topic;
    topic.id = static_cast<std::uint32_t>(sqlite3_column_int64(query.get(), 0));
    topic.topic = column_text(query.get(), 1);
    topic.type = column_text(query.get(), 2);
    const std::string format = column_text(query.get(), 3);
    if (format == "cdr") {
      topic.encoding = MessageEncoding::cdr;
    } else if (format == "ros1") {
      topic.encoding = MessageEncoding::ros1;
    } else {
      warnings.push_back("topic " + topic.topic + " has serialization_format '" + format +
                         "', which floorgrid cannot decode (only cdr and ros1)");
    }
    topics.push_back(std::move(topic));
  }
  require_table(db, "messages");  // read next, by the caller
  return topics;
}

BagContents totals(const std::filesystem::path& path, std::vector<BagTopic> topics,
                   std::vector<std::string> warnings) {
  BagContents contents;
  contents.format = BagFormat::rosbag2_sqlite;
  contents.topics = std::move(topics);
  contents.warnings = std::move(warnings);
  std::error_code ec;
  contents.bytes = std::filesystem::file_size(path, ec);
  add_topic_totals(contents);
  return contents;
}

std::map<std::int64_t, std::size_t> index_by_id(const std::vector<BagTopic>& topics) {
  std::map<std::int64_t, std::size_t> index;
  for (std::size_t i = 0; i < topics.size(); ++i)
    index[topics[i].id] = i;
  return index;
}

[[noreturn]] void unknown_topic(const Database& db, std::int64_t topic_id, std::uint64_t read) {
  throw InputError("its messages table has messages on topic_id " + std::to_string(topic_id) +
                       ", which its topics table lacks; read before it: " + std::to_string(read) +
                       " messages",
                   db.name());
}

BagContents db3_contents(const std::filesystem::path& path, const BagReadLimits& limits) {
  const Database db(path, limits);
  std::vector<std::string> warnings;
  std::vector<BagTopic> topics = read_topics(db, warnings);
  const auto index = index_by_id(topics);
  const auto query = db.prepare(
      "SELECT topic_id, COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages GROUP BY topic_id");
  while (db.step(query.get())) {
    const std::int64_t topic_id = sqlite3_column_int64(query.get(), 0);
    const auto found = index.find(topic_id);
    if (found == index.end())
      unknown_topic(db, topic_id, 0);
    BagTopic& topic = topics[found->second];
    topic.messages = static_cast<std::uint64_t>(sqlite3_column_int64(query.get(), 1));
    topic.first_ns = sqlite3_column_int64(query.get(), 2);
    topic.last_ns = sqlite3_column_int64(query.get(), 3);
  }
  return totals(path, std::move(topics), std::move(warnings));
}

BagContents read_db3(const std::filesystem::path& path, const BagVisitor* visit,
                     const std::set<std::string>* wanted, const BagReadLimits& limits) {
  const Database db(path, limits);
  std::vector<std::string> warnings;
  std::vector<BagTopic> topics = read_topics(db, warnings);
  const auto index = index_by_id(topics);
  std::vector<bool> visited(topics.size());
  for (std::size_t i = 0; i < topics.size(); ++i)
    visited[i] = visit != nullptr && (wanted == nullptr || wanted->count(topics[i].topic) > 0);
  // Every row is read (not only the wanted topics') so that the contents count them all.
  const auto query =
      db.prepare("SELECT topic_id, timestamp, data FROM messages ORDER BY timestamp, id");
  std::uint64_t read = 0;
  while (db.step(query.get())) {
    const std::int64_t topic_id = sqlite3_column_int64(query.get(), 0);
    const auto found = index.find(topic_id);
    if (found == index.end())
      unknown_topic(db, topic_id, read);
    BagTopic& topic = topics[found->second];
    const std::int64_t t = sqlite3_column_int64(query.get(), 1);
    if (topic.messages == 0 || t < topic.first_ns)
      topic.first_ns = t;
    if (topic.messages == 0 || t > topic.last_ns)
      topic.last_ns = t;
    ++topic.messages;
    ++read;
    if (!visited[found->second])
      continue;
    BagMessageView view;
    view.topic_id = topic.id;
    view.log_time_ns = t;
    const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(query.get(), 2));
    view.data = {data, static_cast<std::size_t>(sqlite3_column_bytes(query.get(), 2))};
    (*visit)(topic, view);
  }
  return totals(path, std::move(topics), std::move(warnings));
}

}  // namespace

BagContents rosbag2_sqlite_contents(const std::filesystem::path& path,
                                    const BagReadLimits& limits) {
  return read_bag_files(
      rosbag2_storage_files(path, "sqlite3", ".db3"),
      [&limits](const std::filesystem::path& file, const BagVisitor*) {
        return db3_contents(file, limits);
      },
      nullptr);
}

BagContents read_rosbag2_sqlite(const std::filesystem::path& path, const BagVisitor& visit,
                                const std::set<std::string>* topics, const BagReadLimits& limits) {
  return read_bag_files(
      rosbag2_storage_files(path, "sqlite3", ".db3"),
      [topics, &limits](const std::filesystem::path& file, const BagVisitor* v) {
        return read_db3(file, v, topics, limits);
      },
      &visit);
}

}  // namespace floorgrid::io
