#pragma once

// What every fuzz target shares: the parsers read files, so each input is written to a file of
// a scratch folder of this process (in /dev/shm when there is one: no disk), and an InputError
// is the expected answer to bad input. Anything else (a crash, another exception, a sanitizer
// report, a timeout, an allocation beyond -malloc_limit_mb) is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "floorgrid/core/error.hpp"

namespace floorgrid::fuzz {

/// This process's scratch folder, created once.
inline const std::filesystem::path& scratch() {
  static const std::filesystem::path folder = [] {
    const std::filesystem::path base = std::filesystem::is_directory("/dev/shm")
                                           ? "/dev/shm"
                                           : std::filesystem::temp_directory_path();
    std::filesystem::path f = base / ("floorgrid-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(f);
    return f;
  }();
  return folder;
}

/// Writes `size` bytes to `name` in the scratch folder; returns its path.
inline std::filesystem::path put(const std::string& name, const std::uint8_t* data,
                                 std::size_t size) {
  const std::filesystem::path path = scratch() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

/// Writes a text file in the scratch folder.
inline std::filesystem::path put(const std::string& name, const std::string& text) {
  return put(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

/// The bag readers' limits under fuzzing: a chunk may take 1 MiB (the default, 256 MiB, would let
/// a bomb's mutant spend its time decompressing under the sanitizers). The inputs are at most
/// 8 KiB, so a chunk stating more is a bomb: refused before anything is allocated, through the
/// same check as the real limit.
inline constexpr std::uint64_t kFuzzChunkBytes = 1ull << 20;

/// Runs `read`; bad input (InputError) is a fine answer.
template <typename Read>
void expect_no_crash(const Read& read) {
  try {
    read();
  } catch (const InputError&) {
  }
}

}  // namespace floorgrid::fuzz
