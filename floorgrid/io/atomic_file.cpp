#include "floorgrid/io/atomic_file.hpp"

#include <unistd.h>

#include <csignal>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <sstream>
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

extern "C" void remove_temporaries_and_stop(int signal_number) {
  for (TemporarySlot& slot : g_temporaries) {
    if (slot.live.load())
      ::unlink(slot.path);
  }
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

std::string read_whole_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw InputError("no such file", path.string());
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError("is a folder, not a file", path.string());
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(std::string("cannot open: ") + std::strerror(errno), path.string());
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad())
    throw InputError("read error", path.string());
  return ss.str();
}

}  // namespace floorgrid::io
