// Maps a plan point through a model file with the installed floorgrid, and back; a missing
// file must give an InputError naming it. Usage: consumer MODEL.json X Y
#include <floorgrid/floorgrid.hpp>

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  if (argc != 4)
    return 64;
  std::printf("floorgrid %s\n", floorgrid::version().c_str());
  const floorgrid::Model model = floorgrid::Model::load(argv[1]);
  Eigen::Matrix2Xd point_in_plan(2, 1);
  point_in_plan << std::atof(argv[2]), std::atof(argv[3]);
  const floorgrid::MappedPoints in_grid = model.forward(point_in_plan);
  const floorgrid::MappedPoints back = model.inverse(in_grid.values);
  std::printf("model %s\n", model.name().c_str());
  std::printf("grid %.6f,%.6f %s\n", in_grid.values(0, 0), in_grid.values(1, 0),
              floorgrid::to_string(in_grid.flags[0]).c_str());
  std::printf("round trip %.3g m\n", (back.values - point_in_plan).norm());
  try {
    floorgrid::Model::load("missing-model.json");
  } catch (const floorgrid::InputError& e) {
    std::printf("InputError file %s\n", e.file().c_str());
  }
  return 0;
}
