// Accuracy of every mapping model against known truth (printed as a table):
//  1. simulated office and bent-office (seed 1): pairs sampled along the plan's walls from the
//     exact warp with 5 cm noise, mean error over SPEC's evaluation domain;
//  2. the real Halmstad hand-picked pairs (../shared/data/halmstad/*/pairs, unit 0.05): the
//     leave-one-out error of each model, in pixels, the median over all pairs of all files;
//     for the gt models, gpgt and auto also with fixed RANSAC thresholds of 0.1 m and 1 m
//     (gpgt: 0.5 m and 1 m); the default adapts the threshold to the pairs' noise.
// Usage: mapping_accuracy_eval [models...]   (default: every model)
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <optional>

#include "floorgrid/evaluation/domain.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace fs = std::filesystem;
using namespace floorgrid;

namespace {

double simulated_error(const SimulatedDataset& d, const std::string& model,
                       std::size_t pairs_wanted) {
  const PlanTruth truth = d.truth();
  const VectorFloorplan walls = filter_layers(d.plan, {{"WALLS", "RACKS"}, {}});
  const EvaluationDomain domain = warp_domain(
      walls, d.gridmap, [&](const Eigen::Vector2d& p) { return truth.plan_to_grid(p); });
  Random random(7);
  ReferencePairs pairs;
  const auto n = static_cast<Eigen::Index>(pairs_wanted);
  pairs.points_in_plan.resize(2, n);
  pairs.points_in_grid.resize(2, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d p =
        domain.points_in_plan.col(random.integer(0, domain.points_in_plan.cols() - 1));
    pairs.points_in_plan.col(i) = p;
    pairs.points_in_grid.col(i) =
        truth.plan_to_grid(p) + Eigen::Vector2d(random.normal(0.05), random.normal(0.05));
  }
  MappingOptions options;
  options.model = model;
  auto m = make_mapping(options);
  m->fit(pairs);
  const Eigen::Matrix2Xd mapped = m->forward_batch(domain.points_in_plan);
  const Eigen::Matrix2Xd exact = truth.plan_to_grid_batch(domain.points_in_plan);
  return (mapped - exact).colwise().norm().mean();
}

// `inlier_threshold`: the gt models' fixed RANSAC threshold (gpgt's: that, but at least 0.5 m,
// its fixed default before the adaptive one), or the defaults when unset.
double halmstad_median_px(const fs::path& root, const std::string& model,
                          std::optional<double> inlier_threshold) {
  std::vector<double> errors;
  for (const char* env : {"E5", "F5", "HIH"}) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(root / env / "pairs"))
      files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      const ReferencePairs pairs = io::read_pairs_csv(f, 0.05);
      MappingOptions options;
      options.model = model;
      if (inlier_threshold) {
        options.ransac.inlier_threshold = inlier_threshold;
        options.gpgt_inlier_threshold = std::max(0.5, *inlier_threshold);
      }
      for (const double e : leave_one_out_errors(options, pairs))
        errors.push_back(e / 0.05);
    }
  }
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2),
                   errors.end());
  return errors[errors.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> models(argv + 1, argv + argc);
  const std::vector<std::string> known = mapping_model_names();
  for (const std::string& model : models) {
    if (std::find(known.begin(), known.end(), model) == known.end()) {
      fmt::print(stderr,
                 "mapping_accuracy_eval: unknown model '{}' (known: {})\n"
                 "usage: mapping_accuracy_eval [models...]   (default: every model)\n",
                 model, fmt::join(known, ", "));
      return 2;
    }
  }
  if (models.empty())
    models = known;
  const SimulatedDataset office = simulate("office", 1);
  const SimulatedDataset bent = simulate("bent-office", 1);
  const fs::path halmstad = fs::path(FLOORGRID_DATA_DIR) / "halmstad";
  const bool have_halmstad = fs::exists(halmstad);
  fmt::print("{:<10} {:>14} {:>18} {:>16} {:>14} {:>14}\n", "model", "office mean m",
             "bent-office mean m", "Halmstad LOO px", "(thr. 0.1 m)", "(thr. 1 m)");
  for (const auto& model : models) {
    const double a = simulated_error(office, model, 2000);
    const double b = simulated_error(bent, model, 2000);
    std::string h = "n/a", h_tight = "", h_loose = "";
    if (have_halmstad) {
      h = fmt::format("{:.2f}", halmstad_median_px(halmstad, model, std::nullopt));
      if (model.rfind("gt", 0) == 0 || model == "gpgt" || model == "auto") {
        h_tight = fmt::format("{:.2f}", halmstad_median_px(halmstad, model, 0.10));
        h_loose = fmt::format("{:.2f}", halmstad_median_px(halmstad, model, 1.0));
      }
    }
    fmt::print("{:<10} {:>14.4f} {:>18.4f} {:>16} {:>14} {:>14}\n", model, a, b, h, h_tight,
               h_loose);
  }
  if (!have_halmstad)
    fmt::print("(Halmstad pairs missing: {})\n", halmstad.string());
}
