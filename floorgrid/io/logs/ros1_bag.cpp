// ROS 1 bag 2.0: the contents from the index section (connection and chunk info records, and the
// index data records after the chunks), else by reading the chunks through (ros1_bag_scan).
#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/logs/bag_file.hpp"
#include "floorgrid/io/logs/ros1_bag_file.hpp"
#include "floorgrid/io/logs/ros1_bag_scan.hpp"

namespace floorgrid::io {
namespace {

using ros1::BagFile;

struct TimeSpan {
  std::int64_t first_ns = std::numeric_limits<std::int64_t>::max();
  std::int64_t last_ns = std::numeric_limits<std::int64_t>::min();
};

/// What the index section states: connections in their order, and the chunk infos.
struct BagIndex {
  std::vector<ros1::Connection> connections;
  std::vector<ros1::ChunkInfo> chunks;
};

BagIndex read_index_section(BagFile& file) {
  if (file.index_pos() < file.first_record() || file.index_pos() >= file.size())
    file.fail(0, "its index_pos " + std::to_string(file.index_pos()) +
                     " lies outside the records (the file has " + std::to_string(file.size()) +
                     " bytes)");
  BagIndex index;
  std::vector<std::uint8_t> data;
  for (std::uint64_t offset = file.index_pos(); offset < file.size();) {
    const ros1::Record& record = file.require_record(offset);
    const ros1::Op op = record.header.op();
    if (op == ros1::Op::connection)
      index.connections.push_back(ros1::parse_connection(record.header, file.read_data(data),
                                                         file.name(), record.data_offset));
    else if (op == ros1::Op::chunk_info)
      index.chunks.push_back(ros1::parse_chunk_info(record.header, file.read_data(data),
                                                    file.name(), record.data_offset));
    else
      file.fail(offset,
                "a record of op " + std::to_string(static_cast<int>(op)) +
                    " in the index section (only connections and chunk infos belong there)");
    offset = record.end();
  }
  if (index.connections.size() != file.conn_count() || index.chunks.size() != file.chunk_count())
    file.fail(file.index_pos(), "the bag header states " + std::to_string(file.conn_count()) +
                                    " connections and " + std::to_string(file.chunk_count()) +
                                    " chunks, the index holds " +
                                    std::to_string(index.connections.size()) + " and " +
                                    std::to_string(index.chunks.size()));
  return index;
}

/// The first and last message time per connection in one chunk, from the index data records
/// that follow it.
std::unordered_map<std::uint32_t, TimeSpan> chunk_times(BagFile& file,
                                                        const ros1::ChunkInfo& chunk) {
  const ros1::Record& chunk_record = file.require_record(chunk.chunk_pos);
  if (chunk_record.header.op() != ros1::Op::chunk)
    file.fail(chunk.chunk_pos, "a chunk info points here, but no chunk record is here");
  std::unordered_map<std::uint32_t, TimeSpan> times;
  std::vector<std::uint8_t> data;
  for (std::uint64_t offset = chunk_record.end(); offset < file.size();) {
    const ros1::Record& record = file.require_record(offset);
    if (record.header.op() != ros1::Op::index_data)
      break;
    if (record.header.u32("ver") != 1)
      record.header.fail("index data version " + std::to_string(record.header.u32("ver")) +
                         " (known: 1)");
    const std::uint32_t count = record.header.u32("count");
    ByteCursor cursor(file.read_data(data), file.name(), record.data_offset);
    cursor.require(std::uint64_t{count} * 12, "the index data's entries");
    TimeSpan& span = times[record.header.u32("conn")];
    for (std::uint32_t i = 0; i < count; ++i) {
      const auto sec = cursor.read<std::uint32_t>("an index entry's time");
      const auto nsec = cursor.read<std::uint32_t>("an index entry's time");
      cursor.skip(4, "an index entry's offset");
      span.first_ns = std::min(span.first_ns, ros1::time_ns(sec, nsec));
      span.last_ns = std::max(span.last_ns, ros1::time_ns(sec, nsec));
    }
    offset = record.end();
  }
  return times;
}

/// Per connection, its first and last message time, reading the index data of as few chunks as
/// the chunk infos' time spans allow (a chunk starting after the best first time found cannot
/// hold an earlier one): in a bag recorded in time order, one chunk each way.
void set_topic_times(BagFile& file, const BagIndex& index, BagContents& contents,
                     const std::unordered_map<std::uint32_t, std::size_t>& index_of) {
  std::map<std::size_t, std::unordered_map<std::uint32_t, TimeSpan>> cache;
  const auto times_in = [&](std::size_t k, std::uint32_t conn) {
    auto found = cache.find(k);
    if (found == cache.end())
      found = cache.emplace(k, chunk_times(file, index.chunks[k])).first;
    const auto span = found->second.find(conn);
    if (span == found->second.end() || span->second.first_ns > span->second.last_ns)
      file.fail(index.chunks[k].chunk_pos,
                "the chunk's index data lists no message on "
                "connection " +
                    std::to_string(conn) + ", which its chunk info counts");
    return span->second;
  };
  std::vector<std::size_t> by_start(index.chunks.size()), by_end(index.chunks.size());
  for (std::size_t k = 0; k < index.chunks.size(); ++k)
    by_start[k] = by_end[k] = k;
  std::sort(by_start.begin(), by_start.end(), [&](std::size_t a, std::size_t b) {
    return index.chunks[a].start_ns < index.chunks[b].start_ns;
  });
  std::sort(by_end.begin(), by_end.end(), [&](std::size_t a, std::size_t b) {
    return index.chunks[a].end_ns > index.chunks[b].end_ns;
  });
  const auto holds = [&](std::size_t k, std::uint32_t conn) {
    return std::any_of(index.chunks[k].counts.begin(), index.chunks[k].counts.end(),
                       [&](const auto& c) { return c.first == conn && c.second > 0; });
  };
  for (const auto& [conn, i] : index_of) {
    BagTopic& topic = contents.topics[i];
    if (topic.messages == 0)
      continue;
    TimeSpan best;
    for (const std::size_t k : by_start) {
      if (index.chunks[k].start_ns > best.first_ns)
        break;
      if (holds(k, conn))
        best.first_ns = std::min(best.first_ns, times_in(k, conn).first_ns);
    }
    for (const std::size_t k : by_end) {
      if (index.chunks[k].end_ns < best.last_ns)
        break;
      if (holds(k, conn))
        best.last_ns = std::max(best.last_ns, times_in(k, conn).last_ns);
    }
    topic.first_ns = best.first_ns;
    topic.last_ns = best.last_ns;
  }
}

BagContents contents_from_index(BagFile& file) {
  const BagIndex index = read_index_section(file);
  BagContents contents;
  contents.format = BagFormat::ros1;
  contents.bytes = file.size();
  std::unordered_map<std::uint32_t, std::size_t> index_of;
  for (const ros1::Connection& connection : index.connections) {
    if (!index_of.emplace(connection.id, contents.topics.size()).second)
      continue;
    BagTopic topic;
    topic.id = connection.id;
    topic.topic = connection.topic;
    topic.type = connection.type;
    topic.encoding = MessageEncoding::ros1;
    contents.topics.push_back(std::move(topic));
  }
  bool any = false;
  for (const ros1::ChunkInfo& chunk : index.chunks) {
    for (const auto& [conn, messages] : chunk.counts) {
      const auto found = index_of.find(conn);
      if (found == index_of.end())
        file.fail(chunk.chunk_pos, "a chunk info counts messages on connection " +
                                       std::to_string(conn) + ", which no connection declares");
      contents.topics[found->second].messages += messages;
      contents.messages += messages;
    }
    if (chunk.counts.empty())
      continue;
    contents.start_ns = any ? std::min(contents.start_ns, chunk.start_ns) : chunk.start_ns;
    contents.end_ns = any ? std::max(contents.end_ns, chunk.end_ns) : chunk.end_ns;
    any = true;
  }
  set_topic_times(file, index, contents, index_of);
  return contents;
}

// Errors before any record was read (the magic, the bag header) say so too.
template <typename Read>
BagContents with_context(const std::filesystem::path& path, const Read& read) {
  std::optional<BagFile> file;
  try {
    file.emplace(path);
  } catch (const InputError& e) {
    throw InputError(e.message() + "; read before it: nothing", e.file(), e.line(), e.field());
  }
  return read(*file);
}

}  // namespace

BagContents ros1_bag_contents(const std::filesystem::path& path, const BagReadLimits& limits) {
  return with_context(path, [&limits](BagFile& file) {
    std::string why;
    if (file.index_pos() == 0) {
      why = "It has no index (index_pos is 0: a recording that was not closed)";
    } else {
      try {
        return contents_from_index(file);
      } catch (const InputError& e) {
        why = "Its index is broken (" + e.message() + ")";
      }
    }
    BagContents contents = ros1::scan_bag(file, nullptr, nullptr, limits);
    contents.warnings.insert(contents.warnings.begin(),
                             why + ": its chunks were read through instead.");
    return contents;
  });
}

BagContents read_ros1_bag(const std::filesystem::path& path, const BagVisitor& visit,
                          const std::set<std::string>* topics, const BagReadLimits& limits) {
  return with_context(path, [&](BagFile& file) {
    BagContents contents = ros1::scan_bag(file, visit ? &visit : nullptr, topics, limits);
    if (file.index_pos() == 0)
      contents.warnings.insert(
          contents.warnings.begin(),
          "It has no index (index_pos is 0: a recording that was not closed): read through.");
    return contents;
  });
}

}  // namespace floorgrid::io
