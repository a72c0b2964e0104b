#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "floorgrid/io/files/binary_file.hpp"
#include "floorgrid/io/logs/ros1_bag_records.hpp"

namespace floorgrid::io::ros1 {

/// Where one top-level record lies in the file, with its parsed header.
struct Record {
  std::uint64_t offset = 0;       ///< of its header_len
  RecordHeader header;            ///< valid until the next read_record
  std::uint64_t data_offset = 0;  ///< of its data
  std::uint32_t data_len = 0;     ///< bytes of data
  /// When the record does not fit in the file (it runs past the end), why; else empty. Its
  /// header may then be left unparsed.
  std::string truncated;
  /// The offset just past its data.
  std::uint64_t end() const { return data_offset + data_len; }
};

/// A ROS 1 bag file opened for reading records at given offsets. Every length is checked
/// against the file's size before anything is allocated or read for it, so a lying length
/// neither reads out of bounds nor allocates beyond the file.
class BagFile {
 public:
  /// Opens `path`, checks the "#ROSBAG V2.0" magic and reads the bag header record. Throws
  /// InputError when it cannot be opened or is no ROS 1 bag 2.0.
  explicit BagFile(const std::filesystem::path& path);

  /// The file's name as errors state it.
  const std::string& name() const { return file_.name(); }
  /// Its size in bytes.
  std::uint64_t size() const { return file_.size(); }
  /// The bag header's index_pos: offset of the index section, 0 when it was never written.
  std::uint64_t index_pos() const { return index_pos_; }
  /// The bag header's conn_count.
  std::uint32_t conn_count() const { return conn_count_; }
  /// The bag header's chunk_count.
  std::uint32_t chunk_count() const { return chunk_count_; }
  /// The offset of the first record after the bag header.
  std::uint64_t first_record() const { return first_record_; }

  /// Reads the header of the record at `offset` (its data is not read). A record that runs past
  /// the end comes back with `truncated` set; a corrupt header throws InputError.
  const Record& read_record(std::uint64_t offset);
  /// As read_record, but a record that does not fit throws InputError.
  const Record& require_record(std::uint64_t offset);
  /// Reads the data of the record last read into `buffer` (reused); returns it. Throws
  /// InputError when that record does not fit in the file.
  std::span<const std::uint8_t> read_data(std::vector<std::uint8_t>& buffer);

  /// Throws InputError "file: at byte N: message".
  [[noreturn]] void fail(std::uint64_t offset, const std::string& message) const;

 private:
  std::uint32_t read_u32_at(std::uint64_t offset);

  BinaryFile file_;
  std::uint64_t index_pos_ = 0;
  std::uint32_t conn_count_ = 0;
  std::uint32_t chunk_count_ = 0;
  std::uint64_t first_record_ = 0;
  Record record_;
  std::vector<std::uint8_t> header_bytes_;
};

}  // namespace floorgrid::io::ros1
