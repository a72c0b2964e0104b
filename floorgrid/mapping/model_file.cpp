#include "floorgrid/mapping/model_file.hpp"

#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"

namespace floorgrid {

using nlohmann::json;

namespace model_json {

json points(const Eigen::Matrix2Xd& p) {
  json out = json::array();
  for (Eigen::Index i = 0; i < p.cols(); ++i)
    out.push_back({p(0, i), p(1, i)});
  return out;
}

Eigen::Matrix2Xd points(const json& j, const std::string& where, const std::string& field) {
  if (!j.is_array())
    throw InputError("expected a list of [x, y]", where, 0, field);
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(j.size()));
  for (std::size_t i = 0; i < j.size(); ++i) {
    const json& p = j[i];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) {
      throw InputError("element " + std::to_string(i + 1) + " is not [x, y]", where, 0, field);
    }
    out.col(static_cast<Eigen::Index>(i)) << p[0].get<double>(), p[1].get<double>();
  }
  if (!out.allFinite())
    throw InputError("holds a value that is not finite", where, 0, field);
  return out;
}

json matrix(const Eigen::MatrixXd& m) {
  json out = json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    json row = json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      row.push_back(m(r, c));
    out.push_back(row);
  }
  return out;
}

Eigen::MatrixXd matrix(const json& j, const std::string& where, const std::string& field,
                       Eigen::Index rows, Eigen::Index cols) {
  if (!j.is_array() || j.empty() || !j[0].is_array()) {
    throw InputError("expected a matrix as a list of rows", where, 0, field);
  }
  const auto r = static_cast<Eigen::Index>(j.size()), c = static_cast<Eigen::Index>(j[0].size());
  if ((rows && r != rows) || (cols && c != cols)) {
    throw InputError(
        "expected a " + std::to_string(rows) + " x " + std::to_string(cols) + " matrix", where, 0,
        field);
  }
  Eigen::MatrixXd m(r, c);
  for (Eigen::Index i = 0; i < r; ++i) {
    const json& row = j[static_cast<std::size_t>(i)];
    if (!row.is_array() || static_cast<Eigen::Index>(row.size()) != c) {
      throw InputError("rows differ in length", where, 0, field);
    }
    for (Eigen::Index k = 0; k < c; ++k) {
      if (!row[static_cast<std::size_t>(k)].is_number())
        throw InputError("expected numbers", where, 0, field);
      m(i, k) = row[static_cast<std::size_t>(k)].get<double>();
    }
  }
  if (!m.allFinite())
    throw InputError("holds a value that is not finite", where, 0, field);
  return m;
}

json vector(const Eigen::VectorXd& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i)
    out.push_back(v[i]);
  return out;
}

Eigen::VectorXd vector(const json& j, const std::string& where, const std::string& field) {
  if (!j.is_array())
    throw InputError("expected a list of numbers", where, 0, field);
  Eigen::VectorXd v(static_cast<Eigen::Index>(j.size()));
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_number())
      throw InputError("expected a list of numbers", where, 0, field);
    v[static_cast<Eigen::Index>(i)] = j[i].get<double>();
  }
  if (!v.allFinite())
    throw InputError("holds a value that is not finite", where, 0, field);
  return v;
}

double number(const json& j, const std::string& where, const std::string& field) {
  if (!j.is_number() || !std::isfinite(j.get<double>())) {
    throw InputError("expected a finite number", where, 0, field);
  }
  return j.get<double>();
}

const json& member(const json& j, const std::string& key, const std::string& where,
                   const std::string& field_prefix) {
  if (!j.is_object() || !j.contains(key)) {
    throw InputError("missing field", where, 0, field_prefix + key);
  }
  return j.at(key);
}

}  // namespace model_json

json PointMapping::to_json() const {
  const FitSummary& s = summary_;
  json j;
  j["format"] = kModelFormat;
  j["version"] = kModelVersion;
  j["model"] = name();
  j["frames"] = {{"from", "plan"}, {"to", "grid"}};
  j["units"] = "m";
  j["unit"] = unit_;
  j["pairs"] = {
      {"given", s.pairs_given},
      {"merged", s.pairs_merged},
      {"conflicting", s.pairs_conflicting},
      {"used", s.pairs_used},
      {"reduction",
       {{"applied", s.reduction.applied},
        {"method", s.reduction.applied ? "spatial binning, robust mean per cell" : "none"},
        {"pairs_before", s.reduction.pairs_before},
        {"pairs_after", s.reduction.pairs_after},
        {"cell_size_m", s.reduction.cell_size},
        {"budget", reduction_budget()}}}};
  json fit = {
      {"rms_m", s.rms_m}, {"seconds", s.seconds}, {"warnings", s.warnings}, {"details", s.details}};
  if (s.inliers)
    fit["inliers"] = *s.inliers;
  fit["cv_error_m"] = s.cv_error_m ? json(*s.cv_error_m) : json(nullptr);
  j["fit"] = fit;
  j["options"] = {{"extrapolation_distance_m", common_.extrapolation_distance},
                  {"support_budget", common_.support_budget},
                  {"inverse_tolerance", common_.inverse_tolerance},
                  {"inverse_max_iterations", common_.inverse_max_iterations},
                  {"seed", common_.seed}};
  j["support"] = {{"plan", model_json::points(support_.points_in_plan)},
                  {"grid", model_json::points(support_.points_in_grid)},
                  {"weights", model_json::vector(support_.has_weights()
                                                     ? support_.weights
                                                     : Eigen::VectorXd::Ones(support_.size()))}};
  j["parameters"] = parameters();
  return j;
}

void PointMapping::from_json(const json& j, const std::string& where) {
  using namespace model_json;
  const json& options = member(j, "options", where);
  common_.extrapolation_distance =
      number(member(options, "extrapolation_distance_m", where, "options."), where,
             "options.extrapolation_distance_m");
  unit_ = number(member(j, "unit", where), where, "unit");
  if (!(unit_ > 0.0))
    throw InputError("must be > 0", where, 0, "unit");
  const json& support = member(j, "support", where);
  ReferencePairs pairs;
  pairs.points_in_plan = points(member(support, "plan", where, "support."), where, "support.plan");
  pairs.points_in_grid = points(member(support, "grid", where, "support."), where, "support.grid");
  pairs.weights = vector(member(support, "weights", where, "support."), where, "support.weights");
  if (pairs.points_in_grid.cols() != pairs.size() || pairs.weights.size() != pairs.size() ||
      pairs.empty()) {
    throw InputError("plan, grid and weights differ in length or are empty", where, 0, "support");
  }
  common_.support_budget =
      std::max<std::size_t>(common_.support_budget, static_cast<std::size_t>(pairs.size()));
  build_support(pairs);
  const json& fit = member(j, "fit", where);
  summary_ = FitSummary{};
  summary_.model = name();
  summary_.rms_m = fit.value("rms_m", 0.0);
  summary_.seconds = fit.value("seconds", 0.0);
  if (fit.contains("inliers"))
    summary_.inliers = fit["inliers"].get<std::size_t>();
  if (fit.contains("cv_error_m") && fit["cv_error_m"].is_number())
    summary_.cv_error_m = fit["cv_error_m"].get<double>();
  summary_.details = fit.value("details", json::object());
  const json& p = member(j, "pairs", where);
  summary_.pairs_given = p.value("given", std::size_t{0});
  summary_.pairs_used = p.value("used", std::size_t{0});
  summary_.pairs_merged = p.value("merged", std::size_t{0});
  load_parameters(member(j, "parameters", where), where);
  fitted_ = true;
}

std::unique_ptr<PointMapping> load_mapping(const json& j, const std::string& where) {
  if (!j.is_object() || j.value("format", "") != kModelFormat) {
    throw InputError(
        std::string("not a floorgrid model file (format must be '") + kModelFormat + "')", where, 0,
        "format");
  }
  if (!j.contains("version") || !j["version"].is_number_integer() ||
      j["version"].get<int>() != kModelVersion) {
    throw InputError("model file version " +
                         (j.contains("version") ? j["version"].dump() : std::string("(none)")) +
                         " is not supported (this floorgrid reads version " +
                         std::to_string(kModelVersion) + ")",
                     where, 0, "version");
  }
  const json& frames = model_json::member(j, "frames", where);
  if (frames.value("from", "") != "plan" || frames.value("to", "") != "grid" ||
      j.value("units", "") != "m") {
    throw InputError("expected frames plan -> grid in metres", where, 0, "frames");
  }
  const json& model = model_json::member(j, "model", where);
  if (!model.is_string())
    throw InputError("expected a model name", where, 0, "model");
  MappingOptions options;
  options.model = model.get<std::string>();
  std::unique_ptr<PointMapping> mapping;
  try {
    mapping = make_mapping(options);
  } catch (const InputError& e) {
    throw InputError(e.message(), where, 0, "model");
  }
  mapping->from_json(j, where);
  return mapping;
}

}  // namespace floorgrid
