#include "floorgrid/io/files/line_reader.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

using test::read_file;
using test::run_command;
using test::TempDir;
using test::write_file;

// Compresses `path` with the gzip tool (not our code) into path + ".gz".
std::filesystem::path gzip_with_tool(const std::filesystem::path& path) {
  const auto result = run_command("gzip -kf '" + path.string() + "'");
  EXPECT_EQ(result.status, 0) << result.err;
  return std::filesystem::path(path.string() + ".gz");
}

std::vector<std::string> read_all(const std::filesystem::path& path,
                                  const LineReaderOptions& options = {}) {
  LineReader reader(path, options);
  std::vector<std::string> lines;
  std::string_view line;
  while (reader.next(line)) {
    lines.emplace_back(line);
    EXPECT_EQ(reader.line_number(), lines.size());
  }
  return lines;
}

// Lines of pseudo-random hex, which compress poorly, so a cut gzip file breaks mid-text.
std::vector<std::string> random_lines(std::size_t count) {
  std::mt19937 random(7);
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < count; ++i) {
    std::string line = "line " + std::to_string(i + 1);
    for (int k = 0; k < 8; ++k)
      line += ' ' + std::to_string(random());
    lines.push_back(line);
  }
  return lines;
}

std::string join(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines)
    text += line + "\n";
  return text;
}

TEST(LineReaderTest, PlainFileGivesLinesWithoutEndOfLine) {
  TempDir dir;
  write_file(dir / "a.txt", "first\nsecond\r\n\n  spaced  \nlast without newline");
  LineReader reader(dir / "a.txt");
  EXPECT_FALSE(reader.compressed());
  const std::vector<std::string> lines = read_all(dir / "a.txt");
  const std::vector<std::string> expected = {"first", "second", "", "  spaced  ",
                                             "last without newline"};
  EXPECT_EQ(lines, expected);
}

TEST(LineReaderTest, GzipFileGivesTheSameLinesAsPlain) {
  TempDir dir;
  const std::vector<std::string> expected = random_lines(5000);
  write_file(dir / "log.txt", join(expected));
  const auto gz = gzip_with_tool(dir / "log.txt");
  LineReader reader(gz);
  EXPECT_TRUE(reader.compressed());
  EXPECT_EQ(read_all(gz), expected);
  EXPECT_EQ(read_all(dir / "log.txt"), expected);
}

TEST(LineReaderTest, LinesLongerThanAChunkComeWhole) {
  TempDir dir;
  std::vector<std::string> expected = {std::string(3'000'000, 'x'), "short", std::string(1000, 'y'),
                                       ""};
  write_file(dir / "long.txt", join(expected));
  EXPECT_EQ(read_all(dir / "long.txt"), expected);
  LineReaderOptions tiny;
  tiny.chunk_bytes = 16;
  EXPECT_EQ(read_all(dir / "long.txt", tiny), expected);
  EXPECT_EQ(read_all(gzip_with_tool(dir / "long.txt"), tiny), expected);
}

TEST(LineReaderTest, EmptyFileHasNoLines) {
  TempDir dir;
  write_file(dir / "empty.txt", "");
  EXPECT_TRUE(read_all(dir / "empty.txt").empty());
  EXPECT_FALSE(LineReader(dir / "empty.txt").compressed());
  const auto gz = gzip_with_tool(dir / "empty.txt");
  EXPECT_TRUE(read_all(gz).empty());
  EXPECT_TRUE(LineReader(gz).compressed());
}

TEST(LineReaderTest, MissingFileOrFolderIsInputErrorNamingIt) {
  TempDir dir;
  try {
    LineReader reader(dir / "nope.log");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), (dir / "nope.log").string());
    EXPECT_NE(std::string(error.what()).find("no such file"), std::string::npos);
  }
  EXPECT_THROW(LineReader reader(dir.path()), InputError);
}

TEST(LineReaderTest, TruncatedGzipIsInputErrorNamingFileAndLineReached) {
  TempDir dir;
  const std::vector<std::string> expected = random_lines(20000);
  write_file(dir / "log.txt", join(expected));
  const auto gz = gzip_with_tool(dir / "log.txt");
  const std::string bytes = read_file(gz);
  const auto cut = dir / "cut.txt.gz";
  write_file(cut, bytes.substr(0, bytes.size() / 2));
  // The gzip tool's own count of the complete lines before the cut is the truth.
  const auto complete = run_command("zcat '" + cut.string() + "' 2>/dev/null | wc -l");
  const long complete_lines = std::stol(complete.out);
  ASSERT_GT(complete_lines, 100);

  LineReader reader(cut);
  std::string_view line;
  std::size_t returned = 0;
  try {
    while (reader.next(line)) {
      ASSERT_EQ(line, expected[returned]);
      ++returned;
    }
    FAIL() << "a truncated gzip file read without error";
  } catch (const InputError& error) {
    EXPECT_EQ(static_cast<long>(returned), complete_lines);
    EXPECT_EQ(error.file(), cut.string());
    EXPECT_EQ(error.line(), complete_lines + 1);
    const std::string what = error.what();
    EXPECT_NE(what.find(cut.string() + ":" + std::to_string(complete_lines + 1)), std::string::npos)
        << what;
    EXPECT_NE(what.find("ends early"), std::string::npos) << what;
  }
}

TEST(LineReaderTest, CorruptGzipDataIsInputError) {
  TempDir dir;
  write_file(dir / "log.txt", join(random_lines(20000)));
  std::string bytes = read_file(gzip_with_tool(dir / "log.txt"));
  for (std::size_t i = bytes.size() / 2; i < bytes.size() / 2 + 64; ++i)
    bytes[i] = '\xff';
  write_file(dir / "bad.gz", bytes);
  try {
    read_all(dir / "bad.gz");
    FAIL() << "corrupt gzip data read without error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), (dir / "bad.gz").string());
    EXPECT_GT(error.line(), 1);
  }
}

TEST(LineReaderTest, WrongChecksumIsInputError) {
  TempDir dir;
  write_file(dir / "log.txt", join(random_lines(100)));
  std::string bytes = read_file(gzip_with_tool(dir / "log.txt"));
  bytes[bytes.size() - 8] = static_cast<char>(bytes[bytes.size() - 8] ^ 0x5a);  // CRC-32 trailer
  write_file(dir / "crc.gz", bytes);
  EXPECT_THROW(read_all(dir / "crc.gz"), InputError);
}

TEST(LineReaderTest, OverlongLineIsInputError) {
  TempDir dir;
  write_file(dir / "long.txt", "ok\n" + std::string(5000, 'z') + "\n");
  LineReaderOptions options;
  options.chunk_bytes = 64;
  options.max_line_bytes = 1024;
  try {
    read_all(dir / "long.txt", options);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.line(), 2);
  }
}

TEST(LineReaderTest, TruncatedRealLogIsInputError) {
  FLOORGRID_REQUIRE_DATA("fr079/freiburg-079-corrected.log.gz");
  TempDir dir;
  const std::string bytes = read_file(test::data_path("fr079/freiburg-079-corrected.log.gz"));
  write_file(dir / "cut.log.gz", bytes.substr(0, 1'000'000));
  try {
    read_all(dir / "cut.log.gz");
    FAIL() << "the first half of the fr079 log read without error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), (dir / "cut.log.gz").string());
    EXPECT_GT(error.line(), 1000);
  }
}

}  // namespace
}  // namespace floorgrid::io
