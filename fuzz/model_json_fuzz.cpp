// Model files (io/model_io): every model's parameters, then a mapping through the loaded model
// (a file that loads must map without crashing).
#include "floorgrid/io/formats/model_io.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  const auto path = fuzz::put("model.json", data, size);
  // A GP's lattice is a cache for mapping many points: a small one keeps each input quick.
  MappingOptions options;
  options.gp.prediction.lattice.max_nodes = 4096;
  fuzz::expect_no_crash([&] {
    const auto model = io::read_model(path, options);
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(3.5, -2.0)}) {
      model->map_forward(p);
      model->map_inverse(p);
      model->forward_pose({p.x(), p.y(), 0.5});
    }
  });
  return 0;
}
