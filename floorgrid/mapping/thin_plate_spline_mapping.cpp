#include "floorgrid/mapping/thin_plate_spline_mapping.hpp"

#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid {

ThinPlateSplineMapping::ThinPlateSplineMapping(MappingCommonOptions common,
                                               ThinPlateSplineModelOptions options)
    : PointMapping(std::move(common)), options_(options) {
  if (!(options_.spline.regularization >= 0.0)) {
    throw InputError("must be >= 0 (m^2)", {}, 0, "tps.regularization");
  }
}

ThinPlateSplineMapping::~ThinPlateSplineMapping() = default;

void ThinPlateSplineMapping::fit_model(const ReferencePairs& pairs, FitSummary& summary) {
  spline_.emplace(
      ThinPlateSpline::fit(pairs.points_in_plan, pairs.points_in_grid, options_.spline));
  const Eigen::Matrix2Xd residual =
      spline_->evaluate_batch(pairs.points_in_plan, 2) - pairs.points_in_grid;
  summary.rms_m = std::sqrt(residual.colwise().squaredNorm().mean());
  summary.details = {{"centres", spline_->size()},
                     {"regularization_m2", options_.spline.regularization},
                     {"bending_energy", spline_->bending_energy()}};
}

Eigen::Vector2d ThinPlateSplineMapping::forward(const Eigen::Vector2d& p) const {
  return spline_->evaluate(p);
}

Eigen::Matrix2Xd ThinPlateSplineMapping::forward_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& p) const {
  if (p.cols() < options_.lattice_from)
    return spline_->evaluate_batch(p, 2);
  std::call_once(lattice_once_, [&] {
    Eigen::AlignedBox2d box(support().points_in_plan.rowwise().minCoeff(),
                            support().points_in_plan.rowwise().maxCoeff());
    lattice_ = std::make_unique<ThinPlateSplineLattice>(*spline_, box, options_.lattice);
  });
  return lattice_->evaluate_batch(p);
}

Eigen::Matrix2d ThinPlateSplineMapping::jacobian(const Eigen::Vector2d& p) const {
  return spline_->jacobian(p);
}

nlohmann::json ThinPlateSplineMapping::parameters() const {
  const ThinPlateSplineData& d = spline_->data();
  return {{"centres", model_json::points(d.centres_in_plan)},
          {"kernel_weights", model_json::points(d.kernel_weights)},
          {"affine", model_json::matrix(d.affine)},
          {"regularization_m2", d.regularization},
          {"input_offset", {d.input_offset.x(), d.input_offset.y()}},
          {"input_scale", d.input_scale},
          {"output_offset", {d.output_offset.x(), d.output_offset.y()}},
          {"lattice_spacing_m", options_.lattice.spacing}};
}

void ThinPlateSplineMapping::load_parameters(const nlohmann::json& j, const std::string& where) {
  using namespace model_json;
  const std::string p = "parameters.";
  ThinPlateSplineData d;
  d.centres_in_plan = points(member(j, "centres", where, p), where, p + "centres");
  d.kernel_weights = points(member(j, "kernel_weights", where, p), where, p + "kernel_weights");
  d.affine = matrix(member(j, "affine", where, p), where, p + "affine", 2, 3);
  d.regularization =
      number(member(j, "regularization_m2", where, p), where, p + "regularization_m2");
  const Eigen::VectorXd in = vector(member(j, "input_offset", where, p), where, p + "input_offset");
  const Eigen::VectorXd out =
      vector(member(j, "output_offset", where, p), where, p + "output_offset");
  if (in.size() != 2 || out.size() != 2)
    throw InputError("expected [x, y]", where, 0, p + "input_offset");
  d.input_offset = in;
  d.output_offset = out;
  d.input_scale = number(member(j, "input_scale", where, p), where, p + "input_scale");
  options_.spline.regularization = d.regularization;
  options_.lattice.spacing = j.value("lattice_spacing_m", options_.lattice.spacing);
  try {
    spline_.emplace(std::move(d));
  } catch (const InputError& e) {
    throw InputError(e.message(), where, 0, p + e.field());
  }
}

}  // namespace floorgrid
