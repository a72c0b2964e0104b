#include "floorgrid/io/files/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <utility>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {

namespace {

// The temporary files being written, for the signal handler: fixed slots, so that the handler
// reads only memory that is never freed and calls only unlink() (async-signal-safe).
constexpr std::size_t kSlots = 64;
constexpr std::size_t kPathBytes = 4096;
struct TemporarySlot {
  std::atomic<bool> taken{false};  // owned by an AtomicFile
  std::atomic<bool> live{false};   // `path` holds a complete path to remove
  char path[kPathBytes] = {};
};
TemporarySlot g_temporaries[kSlots];

/// Registers a temporary file; returns its slot, or -1 when none is free or the path too long
/// (the file is then only removed by the AtomicFile itself).
int register_temporary(const std::filesystem::path& path) {
  const std::string text = path.string();
  if (text.size() >= kPathBytes)
    return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (g_temporaries[i].taken.compare_exchange_strong(expected, true)) {
      std::memcpy(g_temporaries[i].path, text.c_str(), text.size() + 1);
      g_temporaries[i].live.store(true);
      return static_cast<int>(i);
    }
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot < 0)
    return;
  g_temporaries[slot].live.store(false);
  g_temporaries[slot].taken.store(false);
}

// The live IncompleteMarker's open file and what it says when the run is interrupted, for the
// signal handler (written before the handler may need it; the handler only writes it out).
std::atomic<int> g_marker_fd{-1};
char g_marker_interrupted[1024] = {};
std::atomic<std::size_t> g_marker_interrupted_bytes{0};

/// Rewrites the marker as interrupted by `signal_number`, with calls safe in a signal handler.
void mark_interrupted(int signal_number) {
  const int fd = g_marker_fd.load();
  if (fd < 0)
    return;
  if (::lseek(fd, 0, SEEK_SET) != 0 || ::ftruncate(fd, 0) != 0)
    return;
  ssize_t ignored = ::write(fd, g_marker_interrupted, g_marker_interrupted_bytes.load());
  char digits[16];
  std::size_t n = 0;
  for (int v = signal_number; v > 0 && n < sizeof digits; v /= 10)
    digits[n++] = static_cast<char>('0' + v % 10);
  char text[32] = "signal ";
  std::size_t length = 7;
  while (n > 0)
    text[length++] = digits[--n];
  text[length++] = '\n';
  ignored = ::write(fd, text, length);
  (void)ignored;
  ::fsync(fd);
}

extern "C" void remove_temporaries_and_stop(int signal_number) {
  for (TemporarySlot& slot : g_temporaries) {
    if (slot.live.load())
      ::unlink(slot.path);
  }
  mark_interrupted(signal_number);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

std::filesystem::path temporary_beside(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path tmp = target;
  tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return tmp;
}
}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(std::move(target)), temporary_(temporary_beside(target_)) {
  slot_ = register_temporary(temporary_);
  stream_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!stream_) {
    unregister_temporary(slot_);
    throw InputError(std::string("cannot write here: ") + std::strerror(errno), target_.string());
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    stream_.close();
    std::error_code ec;
    std::filesystem::remove(temporary_, ec);
  }
  unregister_temporary(slot_);
}

void AtomicFile::commit() {
  stream_.flush();
  const bool ok = static_cast<bool>(stream_);
  stream_.close();
  if (!ok || stream_.fail()) {
    throw InputError("writing failed (disk full?)", target_.string());
  }
  std::error_code ec;
  std::filesystem::rename(temporary_, target_, ec);
  if (ec)
    throw InputError("cannot replace the file: " + ec.message(), target_.string());
  committed_ = true;
  unregister_temporary(slot_);
  slot_ = -1;
}

void remove_temporaries_on_signals() {
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction action = {};
    action.sa_handler = remove_temporaries_and_stop;
    sigemptyset(&action.sa_mask);
    sigaction(signal_number, &action, nullptr);
  }
}

IncompleteMarker::IncompleteMarker(std::filesystem::path folder, const std::string& job)
    : path_(std::move(folder) / kIncompleteMarker) {
  const std::string started =
      job + " (process " + std::to_string(::getpid()) +
      ") is writing this folder. While this file is here, the folder is not a finished result: "
      "the run is still going, or it stopped before it finished (the other files may then be "
      "of this run and of an earlier one). Run it again.\n";
  const std::string interrupted =
      job + " (process " + std::to_string(::getpid()) +
      ") was interrupted while it wrote this folder: the folder is not a finished result (its "
      "files may be of this run and of an earlier one). Run it again. Stopped by ";
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw InputError(std::string("cannot write here: ") + std::strerror(errno), path_.string());
  if (::write(fd_, started.data(), started.size()) != static_cast<ssize_t>(started.size())) {
    ::close(fd_);
    throw InputError("writing failed (disk full?)", path_.string());
  }
  const std::size_t bytes = std::min(interrupted.size(), sizeof g_marker_interrupted);
  std::memcpy(g_marker_interrupted, interrupted.data(), bytes);
  g_marker_interrupted_bytes.store(bytes);
  g_marker_fd.store(fd_);
}

IncompleteMarker::~IncompleteMarker() {
  if (fd_ >= 0) {
    g_marker_fd.store(-1);
    ::close(fd_);
  }
}

void IncompleteMarker::done() {
  if (fd_ < 0)
    return;
  g_marker_fd.store(-1);
  ::close(fd_);
  fd_ = -1;
  std::error_code ec;
  std::filesystem::remove(path_, ec);
}

void write_file_atomically(const std::filesystem::path& path, const std::string& bytes) {
  AtomicFile file(path);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

bool prepare_output_folder(const std::filesystem::path& folder) {
  std::error_code ec;
  const bool existed = std::filesystem::exists(folder, ec);
  std::filesystem::create_directories(folder, ec);
  if (ec || !std::filesystem::is_directory(folder, ec)) {
    throw InputError("cannot create the output folder" + (ec ? ": " + ec.message() : std::string()),
                     folder.string());
  }
  return !existed;
}

OutputFolder::OutputFolder(std::filesystem::path folder)
    : folder_(std::move(folder)), created_(prepare_output_folder(folder_)) {}

OutputFolder::~OutputFolder() {
  std::error_code ec;
  if (created_ && std::filesystem::is_empty(folder_, ec) && !ec)
    std::filesystem::remove(folder_, ec);  // only an empty folder: the job wrote nothing
}

std::string read_whole_file(const std::filesystem::path& path, std::uint64_t max_bytes) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw InputError("no such file", path.string());
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError("is a folder, not a file", path.string());
  }
  const auto too_large = [&] {
    return InputError("holds more than " + std::to_string(max_bytes) +
                          " bytes, more than a file of this kind may (is it the right file?)",
                      path.string());
  };
  std::uintmax_t size = 0;
  if (std::filesystem::is_regular_file(path, ec)) {
    size = std::filesystem::file_size(path, ec);
    if (!ec && size > max_bytes)
      throw too_large();
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(std::string("cannot open: ") + std::strerror(errno), path.string());
  // Read in pieces, counting: a device or pipe has no size to check first.
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(std::min<std::uintmax_t>(size, max_bytes)));
  std::string piece(1 << 16, '\0');
  while (in) {
    in.read(piece.data(), static_cast<std::streamsize>(piece.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (bytes.size() + got > max_bytes)
      throw too_large();
    bytes.append(piece, 0, got);
  }
  if (in.bad())
    throw InputError("read error", path.string());
  return bytes;
}

}  // namespace floorgrid::io
