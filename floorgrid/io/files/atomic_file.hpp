#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace floorgrid::io {

/// A file written atomically: bytes go to a temporary file beside the target, which replaces the
/// target only on commit(). Destroyed without commit(), it removes the temporary file, so an
/// interrupted or failed write never leaves a torn or half-written target.
class AtomicFile {
 public:
  /// Opens a temporary file beside `target`; throws InputError when the folder is not writable.
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// The stream to write to.
  std::ofstream& stream() { return stream_; }
  /// Flushes, checks for write errors and renames the temporary file onto the target.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::ofstream stream_;
  bool committed_ = false;
  int slot_ = -1;  // in the registry of temporaries removed on signals
};

/// Removes every live temporary file of an AtomicFile when the process is told to stop
/// (SIGINT, SIGTERM, SIGHUP), rewrites a live IncompleteMarker to say the run was interrupted,
/// then stops the process as the signal would have: an interrupted run leaves neither a torn
/// target nor a temporary file behind, and says so where it had written files. Call once,
/// early in main().
void remove_temporaries_on_signals();

/// The name of the file that marks an output folder whose writing did not finish.
inline constexpr const char* kIncompleteMarker = "INCOMPLETE.txt";

/// Marks an output folder while a job writes several files into it: `<folder>/INCOMPLETE.txt`
/// says the folder is being written (each file is atomic, but together they are one result).
/// done() removes it. A run stopped by SIGINT, SIGTERM or SIGHUP rewrites it to say it was
/// interrupted (see remove_temporaries_on_signals); one stopped by an error leaves it. A folder
/// holding it is not a finished result, whatever else it holds. One marker at a time.
class IncompleteMarker {
 public:
  /// Writes the marker; `job` names the command ("floorgrid align"). Throws InputError when the
  /// folder is not writable.
  IncompleteMarker(std::filesystem::path folder, const std::string& job);
  /// Leaves the marker unless done() was called (the writing did not finish).
  ~IncompleteMarker();
  IncompleteMarker(const IncompleteMarker&) = delete;
  IncompleteMarker& operator=(const IncompleteMarker&) = delete;

  /// The writing finished: removes the marker.
  void done();

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

/// Writes `bytes` to `path` atomically.
void write_file_atomically(const std::filesystem::path& path, const std::string& bytes);

/// Creates `folder` (and its parents) when missing; throws InputError naming it when it cannot be
/// created or is not a folder. Returns whether the folder itself was created.
bool prepare_output_folder(const std::filesystem::path& folder);

/// The output folder of a command, made before the work starts (so a folder that cannot be made
/// fails at once, not after the job): when the command fails before writing anything into a
/// folder this made, the guard removes it again, so bad input leaves nothing behind.
class OutputFolder {
 public:
  explicit OutputFolder(std::filesystem::path folder);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

 private:
  std::filesystem::path folder_;
  bool created_ = false;
};

/// Bytes a text file of settings may hold at most (a dataset.yaml, map YAML, options file,
/// rosbag2 metadata.yaml, truth.json): far above any real one.
inline constexpr std::uint64_t kMaxSettingsFileBytes = 16ull << 20;
/// Bytes any other file read whole may hold at most (a model file, a pairs or points CSV, a DXF,
/// a map image): a file beyond is refused before it is read.
inline constexpr std::uint64_t kMaxInputFileBytes = 1ull << 30;

/// Reads a whole file as bytes; throws InputError naming the file when it cannot be read, or
/// when it holds more than `max_bytes` (counted while reading, so a device or pipe that never
/// ends, /dev/zero, is refused after `max_bytes` too).
std::string read_whole_file(const std::filesystem::path& path,
                            std::uint64_t max_bytes = kMaxInputFileBytes);

}  // namespace floorgrid::io
