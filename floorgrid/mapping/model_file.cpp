#include "floorgrid/mapping/model_file.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <sstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"

namespace floorgrid {

namespace model_fields {

namespace {

[[noreturn]] void fail(const std::string& message, const std::string& where,
                       const std::string& field) {
  throw InputError(message, where, 0, field);
}

const Value::Array& array_of(const Value& v, std::size_t max, const char* what,
                             const std::string& where, const std::string& field) {
  if (!v.is_array())
    fail(std::string("expected a list of ") + what, where, field);
  if (v.size() > max)
    fail("holds " + std::to_string(v.size()) + " items, more than " + std::to_string(max), where,
         field);
  return v.items();
}

Eigen::Matrix2Xd read_pairs(const Value& v, const std::string& where, const std::string& field,
                            double bound) {
  const Value::Array& items = array_of(v, kMaxPoints, "[x, y]", where, field);
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(items.size()));
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Value& p = items[i];
    if (!p.is_array() || p.size() != 2 || !p.items()[0].is_number() || !p.items()[1].is_number())
      fail("item " + std::to_string(i + 1) + " is not [x, y]", where, field);
    const double x = p.items()[0].as_number(), y = p.items()[1].as_number();
    if (!(std::abs(x) <= bound && std::abs(y) <= bound)) {
      std::ostringstream message;
      message << "item " << i + 1 << " [" << x << ", " << y << "] is not finite or beyond "
              << bound;
      fail(message.str(), where, field);
    }
    out.col(static_cast<Eigen::Index>(i)) << x, y;
  }
  return out;
}

}  // namespace

Value points(const Eigen::Matrix2Xd& p) {
  Value out = Value::array();
  for (Eigen::Index i = 0; i < p.cols(); ++i)
    out.push_back(Value::array({p(0, i), p(1, i)}));
  return out;
}

Eigen::Matrix2Xd points(const Value& v, const std::string& where, const std::string& field) {
  return read_pairs(v, where, field, kMaxCoordinate);
}

Eigen::Matrix2Xd number_pairs(const Value& v, const std::string& where, const std::string& field) {
  return read_pairs(v, where, field, std::numeric_limits<double>::max());
}

Value matrix(const Eigen::MatrixXd& m) {
  Value out = Value::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    Value row = Value::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      row.push_back(m(r, c));
    out.push_back(std::move(row));
  }
  return out;
}

Eigen::MatrixXd matrix(const Value& v, const std::string& where, const std::string& field,
                       Eigen::Index rows, Eigen::Index cols) {
  const std::string shape = std::to_string(rows) + " x " + std::to_string(cols);
  if (!v.is_array() || static_cast<Eigen::Index>(v.size()) != rows)
    fail("expected a " + shape + " matrix as a list of rows", where, field);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r) {
    const Value& row = v.items()[static_cast<std::size_t>(r)];
    if (!row.is_array() || static_cast<Eigen::Index>(row.size()) != cols)
      fail("expected a " + shape + " matrix as a list of rows", where, field);
    for (Eigen::Index c = 0; c < cols; ++c) {
      const Value& x = row.items()[static_cast<std::size_t>(c)];
      if (!x.is_number() || !std::isfinite(x.as_number()))
        fail("expected finite numbers", where, field);
      m(r, c) = x.as_number();
    }
  }
  return m;
}

Value vector(const Eigen::VectorXd& v) {
  Value out = Value::array();
  for (Eigen::Index i = 0; i < v.size(); ++i)
    out.push_back(v[i]);
  return out;
}

Eigen::VectorXd vector(const Value& v, const std::string& where, const std::string& field,
                       Eigen::Index size) {
  const Value::Array& items = array_of(v, kMaxPoints, "numbers", where, field);
  if (size > 0 && static_cast<Eigen::Index>(items.size()) != size)
    fail("expected " + std::to_string(size) + " numbers", where, field);
  Eigen::VectorXd out(static_cast<Eigen::Index>(items.size()));
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (!items[i].is_number() || !std::isfinite(items[i].as_number()))
      fail("expected finite numbers", where, field);
    out[static_cast<Eigen::Index>(i)] = items[i].as_number();
  }
  return out;
}

double number(const Value& v, const std::string& where, const std::string& field, double lo,
              double hi) {
  if (!v.is_number() || !std::isfinite(v.as_number()))
    fail("expected a finite number", where, field);
  const double x = v.as_number();
  if (x < lo || x > hi) {
    std::ostringstream message;
    message << "must be in [" << lo << ", " << hi << "] " << got(x);
    fail(message.str(), where, field);
  }
  return x;
}

std::int64_t integer(const Value& v, const std::string& where, const std::string& field,
                     std::int64_t lo, std::int64_t hi) {
  std::int64_t x = 0;
  if (!v.as_integer(x) || x < lo || x > hi) {
    fail("expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]",
         where, field);
  }
  return x;
}

bool flag(const Value& v, const std::string& where, const std::string& field) {
  if (!v.is_bool())
    fail("expected true or false", where, field);
  return v.as_bool();
}

const std::string& text(const Value& v, const std::string& where, const std::string& field) {
  if (!v.is_string())
    fail("expected a text", where, field);
  return v.as_string();
}

const Value& member(const Value& v, const std::string& key, const std::string& where,
                    const std::string& prefix) {
  if (!v.is_object())
    fail("expected an object", where,
         prefix.empty() ? "(file)" : prefix.substr(0, prefix.size() - 1));
  const Value* m = v.find(key);
  if (m == nullptr)
    fail("missing field", where, prefix + key);
  return *m;
}

const Value* optional_member(const Value& v, const std::string& key) {
  const Value* m = v.find(key);
  return m != nullptr && !m->is_null() ? m : nullptr;
}

}  // namespace model_fields

namespace {

using namespace model_fields;

// Metres per unit of the pairs a model may record: a micrometre to a thousand kilometres.
constexpr double kMinUnit = 1e-6;
constexpr double kMaxUnit = 1e6;

/// A finite number of the fit's summary, or 0 when it is missing or null (the summary is
/// informational: a model file whose fit could not state it still maps).
double summary_number(const Value& fit, const std::string& key, const std::string& where) {
  const Value* v = optional_member(fit, key);
  return v ? number(*v, where, "fit." + key) : 0.0;
}

std::size_t summary_count(const Value& object, const std::string& key, const std::string& where,
                          const std::string& prefix) {
  const Value* v = optional_member(object, key);
  return v ? static_cast<std::size_t>(
                 integer(*v, where, prefix + key, 0, std::numeric_limits<std::int64_t>::max()))
           : 0;
}

/// How the fit's error was cross-validated (absent from files of earlier builds).
CrossValidationRecord cv_record(const Value& cv, const std::string& where) {
  CrossValidationRecord record;
  record.kind = text(member(cv, "kind", where, "fit.cv."), where, "fit.cv.kind");
  if (record.kind != "blocked" && record.kind != "random" && record.kind != "runs") {
    throw InputError("must be blocked, random or runs (got " + record.kind + ")", where, 0,
                     "fit.cv.kind");
  }
  record.folds = summary_count(cv, "folds", where, "fit.cv.");
  if (const Value* size = optional_member(cv, "block_size_m"))
    record.block_size = number(*size, where, "fit.cv.block_size_m", 0.0, kMaxCoordinate);
  record.pairs = summary_count(cv, "pairs", where, "fit.cv.");
  return record;
}

/// The error model of `uncertainty` (absent from files of earlier builds: no std_m then).
ErrorModel error_model_of(const Value& u, const std::string& where) {
  const std::string p = "uncertainty.";
  ErrorModel model;
  model.base_std_m =
      number(member(u, "base_std_m", where, p), where, p + "base_std_m", 0.0, kMaxCoordinate);
  model.growth = number(member(u, "growth", where, p), where, p + "growth", 0.0, 1e6);
  model.residuals = summary_count(u, "residuals", where, p);
  if (const Value* reach = optional_member(u, "max_nearest_m"))
    model.max_nearest_m = number(*reach, where, p + "max_nearest_m", 0.0, kMaxCoordinate);
  if (const Value* shared = optional_member(u, "shared_std_m"))
    model.shared_std_m = number(*shared, where, p + "shared_std_m", 0.0, kMaxCoordinate);
  if (const Value* local = optional_member(u, "local")) {
    const std::string l = p + "local.";
    model.local_radius_m =
        number(member(*local, "radius_m", where, l), where, l + "radius_m", 0.0, 1e3);
    model.local_prior = number(member(*local, "prior", where, l), where, l + "prior", 1e-9, 1e6);
    model.local_points = points(member(*local, "points", where, l), where, l + "points");
    model.local_ratios = vector(member(*local, "ratios", where, l), where, l + "ratios");
    if (model.local_ratios.size() != model.local_points.cols())
      throw InputError("points and ratios differ in number", where, 0, l + "ratios");
    if ((model.local_ratios.array() < 0.0).any())
      throw InputError("must be >= 0", where, 0, l + "ratios");
    model.index_local_points();
  }
  return model;
}

/// Refuses a model that maps its own support points (the pairs it was fitted on) to numbers no
/// fit makes: not finite, or beyond kMaxCoordinate, or farther from their grid partners' box
/// than ten times its size and 100 m. Each field was in range, but together they make no
/// mapping (kernel weights of 1e300 put a plan point at 1e303 m, every export then NaN).
void require_plausible(const PointMapping& mapping, const std::string& where) {
  const ReferencePairs& support = mapping.support();
  Eigen::AlignedBox2d box;
  for (Eigen::Index i = 0; i < support.size(); ++i)
    box.extend(Eigen::Vector2d(support.points_in_grid.col(i)));
  const double margin = 10.0 * box.diagonal().norm() + 100.0;
  const Eigen::Matrix2Xd mapped = mapping.forward_batch(support.points_in_plan);
  for (Eigen::Index i = 0; i < mapped.cols(); ++i) {
    const Eigen::Vector2d q = mapped.col(i);
    if (q.allFinite() && q.cwiseAbs().maxCoeff() <= kMaxCoordinate &&
        box.exteriorDistance(q) <= margin)
      continue;
    std::ostringstream message;
    message << "the model maps its support pair " << i + 1 << " (plan ["
            << support.points_in_plan(0, i) << ", " << support.points_in_plan(1, i) << "], grid ["
            << support.points_in_grid(0, i) << ", " << support.points_in_grid(1, i) << "]) to ["
            << q.x() << ", " << q.y()
            << "]: not a plausible mapping (its parameters are damaged or edited)";
    throw InputError(message.str(), where, 0, "parameters");
  }
}

}  // namespace

Value PointMapping::to_model_file() const {
  const FitSummary& s = summary_;
  Value file = Value::object();
  file["format"] = kModelFormat;
  file["version"] = kModelVersion;
  file["model"] = name();
  file["frames"] = {{"from", "plan"}, {"to", "grid"}};
  file["units"] = "m";
  file["unit"] = unit_;
  file["pairs"] = {
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
  Value fit = {{"rms_m", s.rms_m},
               {"seconds", s.seconds},
               {"warnings", Value(s.warnings)},
               {"details", s.details}};
  if (s.inliers)
    fit["inliers"] = *s.inliers;
  fit["cv_error_m"] = s.cv_error_m ? Value(*s.cv_error_m) : Value(nullptr);
  if (s.cv) {
    fit["cv"] = {{"kind", s.cv->kind},
                 {"folds", s.cv->folds},
                 {"block_size_m", s.cv->block_size},
                 {"pairs", s.cv->pairs}};
  }
  file["fit"] = std::move(fit);
  file["options"] = {{"extrapolation_distance_m", common_.extrapolation_distance},
                     {"max_error_m", common_.max_error},
                     {"support_budget", common_.support_budget},
                     {"inverse_tolerance", common_.inverse_tolerance},
                     {"inverse_max_iterations", common_.inverse_max_iterations},
                     {"seed", common_.seed}};
  file["support"] = {
      {"plan", points(support_.points_in_plan)},
      {"grid", points(support_.points_in_grid)},
      {"weights",
       vector(support_.has_weights() ? support_.weights : Eigen::VectorXd::Ones(support_.size()))}};
  file["parameters"] = parameters();
  if (error_model_) {
    file["uncertainty"] = {
        {"std_m",
         "sqrt(f * (base_std_m^2 + (growth * d)^2) + shared_std_m^2), d: metres from the "
         "nearest pair, f: the local factor (1 without local), shared_std_m: a bias all pairs "
         "share (0 without)"},
        {"meaning",
         "root mean square length of the 2D error: |error| <= std_m about 63%, "
         "<= 2 std_m about 95% of points"},
        {"source", "maximum likelihood on spatially blocked cross-validation residuals"},
        {"base_std_m", error_model_->base_std_m},
        {"growth", error_model_->growth},
        {"residuals", error_model_->residuals},
        {"max_nearest_m", error_model_->max_nearest_m},
        {"shared_std_m", error_model_->shared_std_m}};
    if (error_model_->local_radius_m > 0.0) {
      file["uncertainty"]["local"] = {
          {"factor",
           "Gaussian-weighted mean of the held-out pairs' ratios within 3 radius_m, "
           "with the global fit counted as prior pairs of ratio 1"},
          {"radius_m", error_model_->local_radius_m},
          {"prior", error_model_->local_prior},
          {"points", points(error_model_->local_points)},
          {"ratios", vector(error_model_->local_ratios)}};
    }
  }
  return file;
}

void PointMapping::from_model_file(const Value& file, const std::string& where) {
  {
    const std::lock_guard lock(fold_index_mutex_);
    fold_index_.reset();  // the folds of the model loaded, built on first use
  }
  const Value& options = member(file, "options", where);
  common_.extrapolation_distance =
      number(member(options, "extrapolation_distance_m", where, "options."), where,
             "options.extrapolation_distance_m", 0.0, kMaxCoordinate);
  if (const Value* max_error = optional_member(options, "max_error_m")) {
    common_.max_error = number(*max_error, where, "options.max_error_m", 1e-9, kMaxCoordinate);
  }
  unit_ = number(member(file, "unit", where), where, "unit", kMinUnit, kMaxUnit);
  const Value& support = member(file, "support", where);
  ReferencePairs pairs;
  pairs.points_in_plan = points(member(support, "plan", where, "support."), where, "support.plan");
  pairs.points_in_grid = points(member(support, "grid", where, "support."), where, "support.grid");
  pairs.weights = vector(member(support, "weights", where, "support."), where, "support.weights");
  if (pairs.points_in_grid.cols() != pairs.size() || pairs.weights.size() != pairs.size() ||
      pairs.empty()) {
    throw InputError("plan, grid and weights differ in length or are empty", where, 0, "support");
  }
  if ((pairs.weights.array() < 0.0).any() || pairs.weights.sum() <= 0.0)
    throw InputError("weights must be >= 0 and not all 0", where, 0, "support.weights");
  common_.support_budget =
      std::max<std::size_t>(common_.support_budget, static_cast<std::size_t>(pairs.size()));
  build_support(pairs);
  const Value& fit = member(file, "fit", where);
  summary_ = FitSummary{};
  summary_.model = name();
  summary_.rms_m = summary_number(fit, "rms_m", where);
  summary_.seconds = summary_number(fit, "seconds", where);
  if (optional_member(fit, "inliers"))
    summary_.inliers = summary_count(fit, "inliers", where, "fit.");
  if (optional_member(fit, "cv_error_m"))
    summary_.cv_error_m = summary_number(fit, "cv_error_m", where);
  if (const Value* cv = optional_member(fit, "cv"))
    summary_.cv = cv_record(*cv, where);
  if (const Value* details = optional_member(fit, "details"))
    summary_.details = *details;
  const Value& counts = member(file, "pairs", where);
  summary_.pairs_given = summary_count(counts, "given", where, "pairs.");
  summary_.pairs_used = summary_count(counts, "used", where, "pairs.");
  summary_.pairs_merged = summary_count(counts, "merged", where, "pairs.");
  load_parameters(member(file, "parameters", where), where);
  error_model_.reset();
  if (const Value* uncertainty = optional_member(file, "uncertainty"))
    error_model_ = error_model_of(*uncertainty, where);
  fitted_ = true;
}

std::unique_ptr<PointMapping> load_mapping(const Value& file, const std::string& where) {
  return load_mapping(file, where, MappingOptions{});
}

std::unique_ptr<PointMapping> load_mapping(const Value& file, const std::string& where,
                                           const MappingOptions& base) {
  const Value* format = file.find("format");
  if (!file.is_object() || format == nullptr || !format->is_string() ||
      format->as_string() != kModelFormat) {
    throw InputError(
        std::string("not a floorgrid model file (format must be '") + kModelFormat + "')", where, 0,
        "format");
  }
  const Value* version = file.find("version");
  std::int64_t number = 0;
  if (version == nullptr || !version->as_integer(number) || number != kModelVersion) {
    throw InputError("model file version is not supported (this floorgrid reads version " +
                         std::to_string(kModelVersion) + ")",
                     where, 0, "version");
  }
  const Value& frames = member(file, "frames", where);
  const Value* from = frames.find("from");
  const Value* to = frames.find("to");
  const Value* units = file.find("units");
  if (!from || !to || !units || !from->is_string() || !to->is_string() || !units->is_string() ||
      from->as_string() != "plan" || to->as_string() != "grid" || units->as_string() != "m") {
    throw InputError("expected frames plan -> grid in metres", where, 0, "frames");
  }
  MappingOptions options = base;
  options.model = text(member(file, "model", where), where, "model");
  std::unique_ptr<PointMapping> mapping;
  try {
    mapping = make_mapping(options);
  } catch (const InputError& e) {
    throw InputError(e.message(), where, 0, "model");
  }
  mapping->from_model_file(file, where);
  require_plausible(*mapping, where);
  return mapping;
}

}  // namespace floorgrid
