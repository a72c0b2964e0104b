#include "apps/floorgrid/dataset_run.hpp"

#include <spdlog/spdlog.h>

namespace floorgrid::app {

void report_loading(const io::LoadedDataset& d) {
  for (const std::string& w : d.warnings)
    spdlog::warn("{}", w);
  if (d.unit_decision && !d.unit_decision->overruled())
    spdlog::info("{}: {}", d.manifest.floorplan.string(), d.unit_decision->reason);
}

}  // namespace floorgrid::app
