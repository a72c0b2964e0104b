// An interrupted write leaves nothing behind: the temporary files of every AtomicFile being
// written are removed when the process is told to stop, a folder marked incomplete says it was
// interrupted, and the process still stops by the signal (exit status 128 + signal at the shell).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>

#include "floorgrid/io/files/atomic_file.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

/// Files in `folder`.
std::size_t files_in(const std::filesystem::path& folder) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder))
    ++n;
  return n;
}

/// In a child process: two files half written, one committed, then `signal_number`.
int child_interrupted_by(int signal_number, const std::filesystem::path& folder) {
  const pid_t child = fork();
  if (child == 0) {
    io::remove_temporaries_on_signals();
    io::write_file_atomically(folder / "done.txt", "complete\n");
    io::AtomicFile first(folder / "a.csv");
    first.stream() << std::string(1 << 20, 'x');
    first.stream().flush();
    io::AtomicFile second(folder / "b.csv");
    second.stream() << "partial";
    second.stream().flush();
    std::raise(signal_number);
    _exit(0);  // not reached: the signal stops the process
  }
  int status = 0;
  waitpid(child, &status, 0);
  return status;
}

TEST(AtomicFileSignals, TemporariesAreRemovedAndTheSignalStillStopsTheProcess) {
  for (const int signal_number : {SIGTERM, SIGINT, SIGHUP}) {
    test::TempDir dir;
    const int status = child_interrupted_by(signal_number, dir.path());
    ASSERT_TRUE(WIFSIGNALED(status)) << "signal " << signal_number;
    EXPECT_EQ(WTERMSIG(status), signal_number);
    // Only the committed file is left: no target half written, no temporary.
    EXPECT_EQ(files_in(dir.path()), 1u) << "signal " << signal_number;
    EXPECT_EQ(test::read_file(dir / "done.txt"), "complete\n");
  }
}

/// In a child process: a folder marked incomplete, one file written, then `signal_number`
/// (or, with 0, the writing finished and the marker done).
int child_writing_a_folder(int signal_number, const std::filesystem::path& folder) {
  const pid_t child = fork();
  if (child == 0) {
    io::remove_temporaries_on_signals();
    io::IncompleteMarker marker(folder, "floorgrid test");
    io::write_file_atomically(folder / "metrics.json", "{}\n");
    if (signal_number == 0) {
      marker.done();
      _exit(0);
    }
    std::raise(signal_number);
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  return status;
}

TEST(AtomicFileSignals, AnInterruptedRunSaysSoInTheFolderItWrote) {
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    test::TempDir dir;
    const int status = child_writing_a_folder(signal_number, dir.path());
    ASSERT_TRUE(WIFSIGNALED(status)) << "signal " << signal_number;
    EXPECT_EQ(WTERMSIG(status), signal_number);
    // The file written stays (it is complete), and the marker says the folder is not.
    EXPECT_EQ(test::read_file(dir / "metrics.json"), "{}\n");
    const std::string marker = test::read_file(dir / io::kIncompleteMarker);
    EXPECT_NE(marker.find("floorgrid test (process "), std::string::npos) << marker;
    EXPECT_NE(marker.find("was interrupted while it wrote this folder"), std::string::npos)
        << marker;
    EXPECT_NE(marker.find("Stopped by signal " + std::to_string(signal_number) + "\n"),
              std::string::npos)
        << marker;
    EXPECT_EQ(files_in(dir.path()), 2u);
  }
  test::TempDir dir;
  const int status = child_writing_a_folder(0, dir.path());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_FALSE(std::filesystem::exists(dir / io::kIncompleteMarker));
  EXPECT_EQ(files_in(dir.path()), 1u);
}

}  // namespace
}  // namespace floorgrid
