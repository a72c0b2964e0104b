#include "floorgrid/io/logs/mcap_topics.hpp"

namespace floorgrid::io::mcap {

bool TopicTable::add_schema(const Schema& schema) {
  if (const auto [known, added] = schema_names_.emplace(schema.id, schema.name); !added)
    return known->second == schema.name;
  // A channel may come before its schema (in the summary of some writers).
  for (std::size_t i = 0; i < topics_.size(); ++i)
    if (schema_ids_[i] == schema.id && topics_[i].type.empty())
      topics_[i].type = schema.name;
  return true;
}

bool TopicTable::add_channel(const Channel& channel) {
  if (const auto [known, added] = index_.emplace(channel.id, topics_.size()); !added) {
    const std::size_t i = known->second;
    return topics_[i].topic == channel.topic && schema_ids_[i] == channel.schema_id &&
           encodings_[i] == channel.message_encoding;
  }
  BagTopic topic;
  topic.id = channel.id;
  topic.topic = channel.topic;
  if (channel.message_encoding == "cdr")
    topic.encoding = MessageEncoding::cdr;
  else if (channel.message_encoding == "ros1")
    topic.encoding = MessageEncoding::ros1;
  if (const auto schema = schema_names_.find(channel.schema_id); schema != schema_names_.end())
    topic.type = schema->second;
  topics_.push_back(topic);
  schema_ids_.push_back(channel.schema_id);
  encodings_.push_back(channel.message_encoding);
  wanted_.push_back(wanted_topics_ == nullptr || wanted_topics_->count(channel.topic) > 0);
  return true;
}

BagTopic* TopicTable::count(std::uint16_t channel_id, std::uint64_t log_time) {
  const auto found = index_.find(channel_id);
  if (found == index_.end())
    return nullptr;
  BagTopic& topic = topics_[found->second];
  const auto t = static_cast<std::int64_t>(log_time);
  if (topic.messages == 0 || t < topic.first_ns)
    topic.first_ns = t;
  if (topic.messages == 0 || t > topic.last_ns)
    topic.last_ns = t;
  ++topic.messages;
  ++messages_;
  return &topic;
}

bool TopicTable::wanted(std::uint16_t channel_id) const {
  const auto found = index_.find(channel_id);
  return found != index_.end() && wanted_[found->second];
}

bool TopicTable::set_count(std::uint16_t channel_id, std::uint64_t messages, std::uint64_t first_ns,
                           std::uint64_t last_ns) {
  const auto found = index_.find(channel_id);
  if (found == index_.end())
    return false;
  BagTopic& topic = topics_[found->second];
  messages_ += messages - topic.messages;
  topic.messages = messages;
  topic.first_ns = static_cast<std::int64_t>(first_ns);
  topic.last_ns = static_cast<std::int64_t>(last_ns);
  return true;
}

std::string TopicTable::progress() const {
  std::size_t with_messages = 0;
  for (const BagTopic& topic : topics_)
    with_messages += topic.messages > 0 ? 1 : 0;
  return std::to_string(messages_) + " messages on " + std::to_string(with_messages) + " topics";
}

BagContents TopicTable::contents(std::uint64_t file_bytes) const {
  BagContents contents;
  contents.format = BagFormat::mcap;
  contents.bytes = file_bytes;
  contents.topics = topics_;
  for (std::size_t i = 0; i < topics_.size(); ++i) {
    const BagTopic& topic = contents.topics[i];
    if (encodings_[i] != "cdr" && encodings_[i] != "ros1")
      contents.warnings.push_back("topic " + topic.topic + " has message encoding '" +
                                  encodings_[i] +
                                  "', which floorgrid cannot decode (only cdr and ros1)");
  }
  add_topic_totals(contents);
  return contents;
}

}  // namespace floorgrid::io::mcap
