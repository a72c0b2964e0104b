#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "floorgrid/io/logs/bag_file.hpp"
#include "floorgrid/io/logs/mcap_records.hpp"

namespace floorgrid::io::mcap {

/// The topics of an MCAP file as its Schema and Channel records define them, and the messages
/// counted on each: what BagContents reports.
class TopicTable {
 public:
  /// `wanted`: the topics whose messages are visited (all when null).
  explicit TopicTable(const std::set<std::string>* wanted) : wanted_topics_(wanted) {}

  /// Remembers a schema's name. A repeated id is fine when it says the same (writers repeat
  /// records in chunks and the summary); returns false, keeping the first, when it names
  /// another type.
  bool add_schema(const Schema& schema);
  /// Adds a channel as a topic. A repeated id is fine when it says the same; returns false,
  /// keeping the first, when it names another topic, schema or encoding.
  bool add_channel(const Channel& channel);
  /// Counts a message on `channel_id` logged at `log_time`; its topic, or null when no channel
  /// of that id was defined.
  BagTopic* count(std::uint16_t channel_id, std::uint64_t log_time);
  /// True when messages on `channel_id` are to be visited.
  bool wanted(std::uint16_t channel_id) const;
  /// Sets a channel's count and times (from a summary); false when no such channel.
  bool set_count(std::uint16_t channel_id, std::uint64_t messages, std::uint64_t first_ns,
                 std::uint64_t last_ns);
  /// "N messages on K topics", for errors.
  std::string progress() const;
  /// The contents: topics in the order they were defined, their types from the schemas, the
  /// totals, and a warning per topic whose message encoding floorgrid cannot decode.
  BagContents contents(std::uint64_t file_bytes) const;

 private:
  const std::set<std::string>* wanted_topics_;
  std::unordered_map<std::uint16_t, std::string> schema_names_;
  std::vector<BagTopic> topics_;
  std::vector<std::uint16_t> schema_ids_;                 // per topic (0: none)
  std::vector<std::string> encodings_;                    // per topic, as the channel names it
  std::vector<bool> wanted_;                              // per topic
  std::unordered_map<std::uint16_t, std::size_t> index_;  // channel id -> topic
  std::uint64_t messages_ = 0;
};

}  // namespace floorgrid::io::mcap
