#include "tests/support/bag_writers.hpp"

#include <cstdlib>

namespace floorgrid::test {
namespace {

const std::filesystem::path kBags = std::filesystem::path(FLOORGRID_SOURCE_DIR) / "tests/bags";

}  // namespace

std::filesystem::path bag_records(std::string& why) {
  static const std::filesystem::path log = data_path("fr079/freiburg-079-corrected.log.gz");
  static TempDir folder;
  static const std::filesystem::path records = folder / "fr079.jsonl";
  if (!std::filesystem::exists(log)) {
    why = "shared data missing: " + log.string();
    return {};
  }
  if (!std::filesystem::exists(records)) {
    const CommandResult r =
        run_command("/usr/bin/python3 " + quoted(kBags / "carmen_to_records.py") + " " +
                    quoted(log) + " " + quoted(records) + " --max-scans 120");
    if (r.status != 0) {
      why = "carmen_to_records.py failed: " + r.err;
      return {};
    }
  }
  return records;
}

std::string mcap_writer_missing() {
  if (run_command("node --version").status != 0)
    return "node is not installed (scripts/install-deps.sh installs it)";
  if (!std::filesystem::exists(kBags / "node_modules/@mcap/core"))
    return "tests/bags/node_modules is missing: run `npm ci --prefix tests/bags` (make deps does)";
  return "";
}

BagBytes run_writer(const std::string& command, const std::filesystem::path& work) {
  const std::filesystem::path manifest = work / "manifest.json", dump = work / "dump";
  const CommandResult r =
      run_command(command + " --manifest " + quoted(manifest) + " --dump-dir " + quoted(dump));
  EXPECT_EQ(r.status, 0) << command << "\n" << r.err;
  BagBytes written;
  if (r.status != 0)
    return written;
  const nlohmann::json m = read_json(manifest);
  for (const auto& [topic, t] : m["topics"].items()) {
    TopicBytes& w = written[topic];
    w.type = t["type"];
    w.count = t["count"];
    w.first_ns = std::stoll(t["first_ns"].get<std::string>());
    w.last_ns = std::stoll(t["last_ns"].get<std::string>());
    w.sizes = t["sizes"].get<std::vector<std::uint64_t>>();
    std::string name = topic;
    for (char& c : name)
      c = c == '/' ? '_' : c;
    w.bytes = read_file(dump / (name + ".bin"));
  }
  return written;
}

BagBytes read_all(const std::filesystem::path& path,
                  BagContents (*read)(const std::filesystem::path&, const BagVisitor&,
                                      const std::set<std::string>*, const io::BagReadLimits&),
                  BagContents* contents) {
  BagBytes got;
  const BagContents c = read(
      path,
      [&](const BagTopic& topic, const BagMessageView& message) {
        EXPECT_EQ(topic.id, message.topic_id);
        TopicBytes& t = got[topic.topic];
        t.type = topic.type;
        if (t.count == 0)
          t.first_ns = message.log_time_ns;
        EXPECT_GE(message.log_time_ns, t.last_ns) << topic.topic << ": not in time order";
        t.last_ns = message.log_time_ns;
        ++t.count;
        t.sizes.push_back(message.data.size());
        t.bytes.append(reinterpret_cast<const char*>(message.data.data()), message.data.size());
      },
      nullptr, io::BagReadLimits{});
  if (contents != nullptr)
    *contents = c;
  return got;
}

void expect_same(const BagBytes& written, const BagBytes& read) {
  ASSERT_EQ(written.size(), read.size());
  for (const auto& [topic, w] : written) {
    SCOPED_TRACE(topic);
    ASSERT_TRUE(read.count(topic));
    const TopicBytes& r = read.at(topic);
    EXPECT_EQ(w.type, r.type);
    EXPECT_EQ(w.count, r.count);
    EXPECT_EQ(w.first_ns, r.first_ns);
    EXPECT_EQ(w.last_ns, r.last_ns);
    EXPECT_EQ(w.sizes, r.sizes);
    EXPECT_TRUE(w.bytes == r.bytes) << "the serialized bytes differ";
  }
}

void expect_contents(const BagBytes& written, const BagContents& contents) {
  ASSERT_EQ(contents.topics.size(), written.size());
  std::uint64_t total = 0;
  std::set<std::uint32_t> ids;
  for (const BagTopic& topic : contents.topics) {
    SCOPED_TRACE(topic.topic);
    ASSERT_TRUE(written.count(topic.topic));
    const TopicBytes& w = written.at(topic.topic);
    EXPECT_EQ(topic.type, w.type);
    EXPECT_EQ(topic.encoding, io::MessageEncoding::cdr);
    EXPECT_EQ(topic.messages, w.count);
    EXPECT_EQ(topic.first_ns, w.first_ns);
    EXPECT_EQ(topic.last_ns, w.last_ns);
    EXPECT_TRUE(ids.insert(topic.id).second) << "topic ids repeat";
    total += w.count;
  }
  EXPECT_EQ(contents.messages, total);
  EXPECT_GT(contents.bytes, 0u);
}

}  // namespace floorgrid::test
