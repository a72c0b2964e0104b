// `floorgrid serve`'s bad input: every mistake ends with exit status 2 and a message naming the
// option, before anything listens. (The API itself is tested in tests/server over loopback.)
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::test {
namespace {

TEST(ServeCommand, EveryMistakeNamesTheOptionAndListensNowhere) {
  const std::filesystem::path root =
      std::filesystem::temp_directory_path() / "floorgrid-serve-test";
  std::filesystem::remove_all(root);
  // An align folder (a model.json, no dataset.yaml) and a dataset folder.
  std::filesystem::create_directories(root / "align");
  MappingOptions options;
  options.model = "gt";
  const auto model = make_mapping(options);
  model->fit(pairs_of({{0, 0}, {4, 0}, {0, 3}, {4, 3}}, {{1, 2}, {5, 2}, {1, 5}, {5, 5}}));
  io::write_model(*model, root / "align" / "model.json");
  // Two more: one whose metrics.json is torn, one whose names no dataset.
  for (const char* name : {"torn", "unnamed"}) {
    std::filesystem::create_directories(root / name);
    std::filesystem::copy_file(root / "align" / "model.json", root / name / "model.json");
  }
  write_file(root / "torn" / "metrics.json", "{\"dataset_path\": ");
  write_file(root / "unnamed" / "metrics.json", "{\"dataset\": \"office\"}");
  std::filesystem::create_directories(root / "dataset");
  write_file(root / "dataset" / "dataset.yaml", "floorplan: plan.png\n");

  const struct {
    std::string args, says;
  } cases[] = {
      {quoted(root / "nowhere"), "no such file"},
      {quoted(root / "align"), "--dataset"},
      {quoted(root / "torn"), "not a JSON object"},
      {quoted(root / "unnamed"), "--dataset"},
      {quoted(root / "dataset"), "--model"},
      {quoted(root / "dataset") + " --model " + quoted(root / "align" / "model.json") +
           " --dataset " + quoted(root / "dataset"),
       "given twice"},
      {quoted(root / "align") + " --dataset " + quoted(root / "dataset") + " --port 70000",
       "--port"},
      // --replay needs the run's track, which an align folder from the maps alone lacks.
      {quoted(root / "align") + " --dataset " + quoted(root / "dataset") + " --replay",
       "scans.csv"},
      {quoted(root / "align") + " --dataset " + quoted(root / "dataset") + " --speed 2",
       "--replay"},
      {quoted(root / "align") + " --dataset " + quoted(root / "dataset") + " --replay --speed 0",
       "--speed"},
  };
  for (const auto& c : cases) {
    const CommandResult r = run_floorgrid("serve " + c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(r.out.find("serving"), std::string::npos) << c.args << "\n" << r.out;
  }
  std::filesystem::remove_all(root);
}

}  // namespace
}  // namespace floorgrid::test
