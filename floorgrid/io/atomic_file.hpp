#pragma once

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
/// (SIGINT, SIGTERM, SIGHUP), then stops it as the signal would have: an interrupted run leaves
/// neither a torn target nor a temporary file behind. Call once, early in main().
void remove_temporaries_on_signals();

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

/// Reads a whole file as bytes; throws InputError naming the file when it cannot be read.
std::string read_whole_file(const std::filesystem::path& path);

}  // namespace floorgrid::io
