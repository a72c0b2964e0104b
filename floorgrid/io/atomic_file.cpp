#include "floorgrid/io/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <sstream>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {

namespace {
std::filesystem::path temporary_beside(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path tmp = target;
  tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return tmp;
}
}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(std::move(target)), temporary_(temporary_beside(target_)) {
  stream_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!stream_) {
    throw InputError(std::string("cannot write here: ") + std::strerror(errno), target_.string());
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    stream_.close();
    std::error_code ec;
    std::filesystem::remove(temporary_, ec);
  }
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
}

void write_file_atomically(const std::filesystem::path& path, const std::string& bytes) {
  AtomicFile file(path);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

void prepare_output_folder(const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec || !std::filesystem::is_directory(folder)) {
    throw InputError("cannot create the output folder" + (ec ? ": " + ec.message() : std::string()),
                     folder.string());
  }
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
