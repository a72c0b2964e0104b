// Bag read speed: read_ros1_bag and read_mcap over a ROS 1 bag and an MCAP file of LaserScan-sized
// messages, written at bench time (never committed) with chunks uncompressed and lz4. A speed
// test, not a correctness test: the files are written by the few lines below (the correctness
// tests use python3-rosbag's bags and @mcap/core's files).
//
// FLOORGRID_BAG_BENCH_MB sets the bag's size in MB (default 1024); FLOORGRID_BAG_BENCH_DIR the
// folder it is written to (default the temp folder). Counters: MB/s of the file read, and the
// process's peak RSS, which stays near a chunk's size (the bag is never held whole).
#include <benchmark/benchmark.h>
#include <lz4frame.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "floorgrid/io/logs/bag_file.hpp"

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kChunkThreshold = 768 * 1024;  // rosbag's default
constexpr std::size_t kBeams = 720;                  // a 0.25-degree 180-degree scanner

std::uint64_t bench_bytes() {
  const char* mb = std::getenv("FLOORGRID_BAG_BENCH_MB");
  return static_cast<std::uint64_t>(mb != nullptr ? std::atof(mb) : 1024.0) * 1024 * 1024;
}

fs::path bench_dir() {
  const char* dir = std::getenv("FLOORGRID_BAG_BENCH_DIR");
  return dir != nullptr ? fs::path(dir) : fs::temp_directory_path();
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in kB on Linux
}

template <typename T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

void field(std::string& header, const std::string& name, const std::string& value) {
  put(header, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
  header += name + "=" + value;
}

template <typename T>
std::string raw(T value) {
  std::string out;
  put(out, value);
  return out;
}

std::string time_field(std::uint32_t sec, std::uint32_t nsec) {
  return raw(sec) + raw(nsec);
}

std::string record(const std::string& header, const std::string& data) {
  std::string out;
  put(out, static_cast<std::uint32_t>(header.size()));
  out += header;
  put(out, static_cast<std::uint32_t>(data.size()));
  return out + data;
}

std::string connection_record() {
  std::string header, details;
  field(header, "op", std::string(1, '\x07'));
  field(header, "conn", raw(std::uint32_t{0}));
  field(header, "topic", "/scan");
  field(details, "topic", "/scan");
  field(details, "type", "sensor_msgs/LaserScan");
  field(details, "md5sum", "90c7ef2dc6895d81024acba2ac42f369");
  field(details, "message_definition", "Header header\nfloat32 angle_min\n...");
  return record(header, details);
}

// A LaserScan's serialization: header (seq, stamp, frame_id), 7 floats, ranges, intensities.
std::string laser_scan(std::uint32_t seq, std::uint32_t sec, std::uint32_t nsec) {
  std::string out;
  put(out, seq);
  put(out, sec);
  put(out, nsec);
  put(out, std::uint32_t{5});
  out += "laser";
  for (const float v : {-1.5708f, 1.5708f, 0.00436f, 0.0f, 0.1f, 0.02f, 30.0f})
    put(out, v);
  put(out, static_cast<std::uint32_t>(kBeams));
  for (std::size_t i = 0; i < kBeams; ++i)  // a room's walls, with a little noise
    put(out, static_cast<float>(3.0 + std::sin(0.01 * static_cast<double>(i + seq)) +
                                0.001 * static_cast<double>((i * 7919 + seq * 104729) % 97)));
  put(out, std::uint32_t{0});
  return out;
}

/// `plain` as one LZ4 frame, in `packed` (returned).
const std::string& lz4_frame(const std::string& plain, std::string& packed) {
  LZ4F_preferences_t preferences{};
  preferences.frameInfo.blockSizeID = LZ4F_max4MB;
  packed.resize(LZ4F_compressFrameBound(plain.size(), &preferences));
  packed.resize(
      LZ4F_compressFrame(packed.data(), packed.size(), plain.data(), plain.size(), &preferences));
  return packed;
}

/// Writes a bag of about `bytes` bytes; returns its path.
fs::path write_bag(const std::string& compression, std::uint64_t bytes) {
  const fs::path path = bench_dir() / ("floorgrid-ros1-bench-" + compression + ".bag");
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << "#ROSBAG V2.0\n";
  const auto bag_header = [](std::uint64_t index_pos, std::uint32_t chunks) {
    std::string header;
    field(header, "op", std::string(1, '\x03'));
    field(header, "index_pos", raw(index_pos));
    field(header, "conn_count", raw(std::uint32_t{1}));
    field(header, "chunk_count", raw(chunks));
    return record(header, std::string(4096 - 8 - header.size(), ' '));
  };
  const std::string placeholder = bag_header(0, 0);
  out << placeholder;
  std::string chunk_infos, plain, packed;
  std::uint32_t seq = 0, chunks = 0;
  std::uint64_t written = 13 + placeholder.size();
  while (written < bytes) {
    const std::uint64_t chunk_pos = written;
    const std::uint32_t first_sec = 1000 + seq / 40;
    plain = chunks == 0 ? connection_record() : std::string();
    std::uint32_t count = 0;
    std::string index_entries;
    while (plain.size() < kChunkThreshold) {
      const std::uint32_t sec = 1000 + seq / 40, nsec = (seq % 40) * 25'000'000;
      std::string header;
      field(header, "op", std::string(1, '\x02'));
      field(header, "conn", raw(std::uint32_t{0}));
      field(header, "time", time_field(sec, nsec));
      index_entries += time_field(sec, nsec) + raw(static_cast<std::uint32_t>(plain.size()));
      plain += record(header, laser_scan(seq, sec, nsec));
      ++seq;
      ++count;
    }
    const std::string* data = compression == "lz4" ? &lz4_frame(plain, packed) : &plain;
    std::string header;
    field(header, "op", std::string(1, '\x05'));
    field(header, "compression", compression);
    field(header, "size", raw(static_cast<std::uint32_t>(plain.size())));
    const std::string chunk = record(header, *data);
    std::string index_header;
    field(index_header, "op", std::string(1, '\x04'));
    field(index_header, "ver", raw(std::uint32_t{1}));
    field(index_header, "conn", raw(std::uint32_t{0}));
    field(index_header, "count", raw(count));
    const std::string index = record(index_header, index_entries);
    out << chunk << index;
    written += chunk.size() + index.size();
    std::string info;
    field(info, "op", std::string(1, '\x06'));
    field(info, "ver", raw(std::uint32_t{1}));
    field(info, "chunk_pos", raw(chunk_pos));
    field(info, "start_time", time_field(first_sec, 0));
    field(info, "end_time", time_field(1000 + (seq - 1) / 40, ((seq - 1) % 40) * 25'000'000));
    field(info, "count", raw(std::uint32_t{1}));
    chunk_infos += record(info, raw(std::uint32_t{0}) + raw(count));
    ++chunks;
  }
  out << connection_record() << chunk_infos;
  out.seekp(13);
  out << bag_header(written, chunks);
  return path;
}

// ---- MCAP: records are opcode u8, length u64, content; strings u32 length + bytes ----

std::string mcap_string(const std::string& s) {
  return raw(static_cast<std::uint32_t>(s.size())) + s;
}

std::string mcap_record(std::uint8_t op, const std::string& content) {
  std::string out(1, static_cast<char>(op));
  put(out, static_cast<std::uint64_t>(content.size()));
  return out + content;
}

/// Writes an MCAP file of about `bytes` bytes (no summary: read through); returns its path.
fs::path write_mcap(const std::string& compression, std::uint64_t bytes) {
  const fs::path path = bench_dir() / ("floorgrid-mcap-bench-" + compression + ".mcap");
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  const std::string magic("\x89MCAP0\r\n", 8);
  out << magic << mcap_record(0x01, mcap_string("ros2") + mcap_string("floorgrid bench"))
      << mcap_record(0x03, raw(std::uint16_t{1}) + mcap_string("sensor_msgs/msg/LaserScan") +
                               mcap_string("ros2msg") + mcap_string("float32 angle_min\n..."))
      << mcap_record(0x04, raw(std::uint16_t{1}) + raw(std::uint16_t{1}) + mcap_string("/scan") +
                               mcap_string("cdr") + raw(std::uint32_t{0}));
  std::uint64_t written = static_cast<std::uint64_t>(out.tellp());
  std::uint32_t seq = 0;
  std::string plain, packed;
  while (written < bytes) {
    plain.clear();
    const std::uint64_t first_ns = 1'000'000'000'000ULL + seq * 25'000'000ULL;
    while (plain.size() < kChunkThreshold) {
      const std::uint64_t ns = 1'000'000'000'000ULL + seq * 25'000'000ULL;
      plain += mcap_record(0x05, raw(std::uint16_t{1}) + raw(seq) + raw(ns) + raw(ns) +
                                     std::string("\0\x01\0\0", 4) +
                                     laser_scan(seq, static_cast<std::uint32_t>(ns / 1'000'000'000),
                                                static_cast<std::uint32_t>(ns % 1'000'000'000)));
      ++seq;
    }
    const std::string* data = compression == "lz4" ? &lz4_frame(plain, packed) : &plain;
    const std::uint64_t last_ns = 1'000'000'000'000ULL + (seq - 1) * 25'000'000ULL;
    const std::string chunk = mcap_record(
        0x06, raw(first_ns) + raw(last_ns) + raw(static_cast<std::uint64_t>(plain.size())) +
                  raw(std::uint32_t{0}) + mcap_string(compression == "none" ? "" : compression) +
                  raw(static_cast<std::uint64_t>(data->size())) + *data);
    out << chunk;
    written += chunk.size();
  }
  out << mcap_record(0x0F, raw(std::uint32_t{0}))
      << mcap_record(0x02, raw(std::uint64_t{0}) + raw(std::uint64_t{0}) + raw(std::uint32_t{0}))
      << magic;
  return path;
}

using ReadBag = floorgrid::io::BagContents (*)(const fs::path&, const floorgrid::io::BagVisitor&,
                                               const std::set<std::string>*,
                                               const floorgrid::io::BagReadLimits&);

void read_bench(benchmark::State& state, const fs::path& path, ReadBag read) {
  const double file_mb = static_cast<double>(fs::file_size(path)) / (1024.0 * 1024.0);
  std::uint64_t messages = 0, payload = 0;
  for (auto _ : state) {
    messages = payload = 0;
    read(
        path,
        [&](const floorgrid::io::BagTopic&, const floorgrid::io::BagMessageView& message) {
          ++messages;
          payload += message.data.size();
        },
        nullptr, floorgrid::io::BagReadLimits{});
    benchmark::DoNotOptimize(payload);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(fs::file_size(path)));
  state.counters["file_MB"] = file_mb;
  state.counters["messages"] = static_cast<double>(messages);
  state.counters["peak_rss_MB"] = peak_rss_mb();
  fs::remove(path);
}
void BM_ReadRos1Bag(benchmark::State& state, const std::string& compression) {
  read_bench(state, write_bag(compression, bench_bytes()), &floorgrid::io::read_ros1_bag);
}
void BM_ReadMcap(benchmark::State& state, const std::string& compression) {
  read_bench(state, write_mcap(compression, bench_bytes()), &floorgrid::io::read_mcap);
}
BENCHMARK_CAPTURE(BM_ReadRos1Bag, none, std::string("none"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_ReadRos1Bag, lz4, std::string("lz4"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_ReadMcap, none, std::string("none"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_ReadMcap, lz4, std::string("lz4"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
