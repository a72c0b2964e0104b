// Dataset manifests (io/dataset_manifest): every key, with small valid files beside it that a
// manifest may name (plan.pgm, gridmap.yaml + gridmap.pgm, log.carmen, pairs.csv).
#include "floorgrid/io/dataset/dataset_manifest.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  static const bool files = [] {
    std::string pgm = "P5\n8 6\n255\n";
    for (int i = 0; i < 48; ++i)
      pgm += static_cast<char>(i % 5 == 0 ? 0 : 254);
    fuzz::put("plan.pgm", pgm);
    fuzz::put("gridmap.pgm", pgm);
    fuzz::put("gridmap.yaml",
              "image: gridmap.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"
              "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
    fuzz::put("log.carmen", "ODOM 0 0 0 0 0 0 1 h 1\nFLASER 3 1 2 3 0 0 0 0 0 0 1 h 1\n");
    fuzz::put("pairs.csv", "plan_x,plan_y,grid_x,grid_y\n0,0,1,1\n1,0,2,1\n0,1,1,2\n");
    return true;
  }();
  (void)files;
  const auto path = fuzz::put("dataset.yaml", data, size);
  fuzz::expect_no_crash([&] { io::read_manifest(path); });
  return 0;
}
