#include "floorgrid/simulation/simulation_preset.hpp"

#include "floorgrid/core/error.hpp"

namespace floorgrid {

std::vector<std::string> simulation_preset_names() {
  return {"office", "warehouse", "bent-office", "office-inches"};
}

SimulationPreset simulation_preset(const std::string& name) {
  SimulationPreset p;
  p.name = name;
  if (name == "office")
    return p;
  if (name == "warehouse") {
    p.building = "warehouse";
    p.max_range = 50.0;
    p.bend_deviation = 0.5;
    p.tour.speed = 1.0;
    return p;
  }
  if (name == "bent-office") {
    p.bend_deviation = 1.0;
    p.max_bend_strain = 0.015;
    return p;
  }
  if (name == "office-inches") {
    // The unit mix-up is the plan's error: coordinates in inches under a header saying mm.
    p.drawing_units = "in";
    p.header_units = "mm";
    p.max_plan_scale_error = 0.0;
    return p;
  }
  std::string known;
  for (const auto& n : simulation_preset_names())
    known += (known.empty() ? "" : ", ") + n;
  throw InputError("unknown preset '" + name + "' (known: " + known + ")", {}, 0, "--preset");
}

}  // namespace floorgrid
