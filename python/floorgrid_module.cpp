// The compiled part of the Python module `floorgrid` (floorgrid._floorgrid): the integrator's
// surface (floorgrid/floorgrid.hpp) with numpy arrays in and out. The pure-Python part
// (python/floorgrid/__init__.py) gives it its documented classes.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <exception>
#include <optional>

#include "floorgrid/floorgrid.hpp"

namespace py = pybind11;
using namespace py::literals;

namespace {

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// UTF-8 text as a Python str, bytes that are not UTF-8 replaced.
py::str text(const std::string& utf8) {
  PyObject* decoded =
      PyUnicode_DecodeUTF8(utf8.data(), static_cast<Py_ssize_t>(utf8.size()), "replace");
  if (!decoded)
    throw py::error_already_set();
  return py::reinterpret_steal<py::str>(decoded);
}

/// A file name as os.fsdecode gives it (undecodable bytes kept as surrogates).
py::str path_text(const std::string& path) {
  PyObject* decoded =
      PyUnicode_DecodeFSDefaultAndSize(path.data(), static_cast<Py_ssize_t>(path.size()));
  if (!decoded)
    throw py::error_already_set();
  return py::reinterpret_steal<py::str>(decoded);
}

/// Rows (2: points, 3: poses) of an N x 2 or N x 3 array; ValueError otherwise.
Eigen::Index columns_of(const Points& points) {
  if (points.ndim() != 2 || (points.shape(1) != 2 && points.shape(1) != 3))
    throw py::value_error("points must be an N x 2 (x, y) or N x 3 (x, y, theta) array");
  return points.shape(1);
}

/// Maps an N x 2 or N x 3 float64 array without copying it; the outputs are numpy arrays the
/// mapping writes into directly.
py::tuple map_points(const floorgrid::Model& model, const Points& points, bool inverse) {
  const Eigen::Index rows = columns_of(points);
  const Eigen::Index n = points.shape(0);
  py::array_t<double> values({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(rows)});
  py::array_t<double> std_m(n), nearest(n);
  py::array_t<std::uint8_t> flags(n);
  // Row-major N x k is column-major k x N: Eigen maps the numpy buffers as they are.
  const Eigen::Map<const Eigen::MatrixXd> in(points.data(), rows, n);
  Eigen::Map<Eigen::MatrixXd> out(values.mutable_data(), rows, n);
  Eigen::Map<Eigen::VectorXd> std_out(std_m.mutable_data(), n);
  Eigen::Map<Eigen::VectorXd> nearest_out(nearest.mutable_data(), n);
  Eigen::Map<Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1>> flags_out(flags.mutable_data(), n);
  {
    py::gil_scoped_release release;
    model.map(in, inverse, out, std_out, nearest_out, flags_out);
  }
  return py::make_tuple(values, std_m, nearest, flags);
}

floorgrid::io::JobOverrides overrides(const std::optional<std::string>& config,
                                      const std::optional<std::string>& options_text,
                                      std::optional<std::uint64_t> seed, std::optional<int> cv,
                                      std::optional<std::string> cv_kind,
                                      std::optional<double> cv_block,
                                      std::optional<double> memory_limit,
                                      std::optional<std::string> pairs_from) {
  floorgrid::io::JobOverrides o;
  o.config = config.value_or("");
  o.options_text = options_text.value_or("");
  o.options_source = "options";
  o.seed = seed;
  o.cv = cv;
  o.cv_kind = std::move(cv_kind);
  o.cv_block = cv_block;
  o.memory_gb = memory_limit;
  o.pairs_from = std::move(pairs_from);
  return o;
}

/// The pairs as an N x 4 array: plan_x, plan_y, grid_x, grid_y (metres).
py::array_t<double> pairs_array(const floorgrid::ReferencePairs& pairs) {
  const auto n = static_cast<py::ssize_t>(pairs.size());
  py::array_t<double> out({n, static_cast<py::ssize_t>(4)});
  auto a = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) {
    a(i, 0) = pairs.points_in_plan(0, i);
    a(i, 1) = pairs.points_in_plan(1, i);
    a(i, 2) = pairs.points_in_grid(0, i);
    a(i, 3) = pairs.points_in_grid(1, i);
  }
  return out;
}

/// N x 4 (or N x 5 with weights) pairs in `unit`s as ReferencePairs in metres.
floorgrid::ReferencePairs pairs_from_array(const Points& array, double unit) {
  if (array.ndim() != 2 || (array.shape(1) != 4 && array.shape(1) != 5))
    throw py::value_error(
        "pairs must be an N x 4 (plan_x, plan_y, grid_x, grid_y) or N x 5 (..., weight) array");
  const auto n = static_cast<Eigen::Index>(array.shape(0));
  const auto a = array.unchecked<2>();
  floorgrid::ReferencePairs pairs;
  pairs.points_in_plan.resize(2, n);
  pairs.points_in_grid.resize(2, n);
  if (array.shape(1) == 5)
    pairs.weights.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    pairs.points_in_plan.col(i) << a(i, 0) * unit, a(i, 1) * unit;
    pairs.points_in_grid.col(i) << a(i, 2) * unit, a(i, 3) * unit;
    if (array.shape(1) == 5)
      pairs.weights[i] = a(i, 4);
  }
  return pairs;
}

floorgrid::Model fit_model(const Points& array, const std::string& kind, int cv,
                           const std::string& cv_kind, double cv_block, double unit,
                           std::uint64_t seed, std::optional<long long> budget,
                           std::optional<double> extrapolation, std::optional<double> max_error,
                           std::optional<double> inlier_threshold,
                           std::optional<double> memory_limit) {
  using floorgrid::InputError;
  if (cv < 0 || cv == 1)
    throw InputError("must be 0 or at least 2", {}, 0, "cv");
  if (!(unit > 0.0 && unit <= floorgrid::kMaxCoordinate))
    throw InputError("must be a positive number of metres per unit", {}, 0, "unit");
  floorgrid::ModelFitRequest request;
  request.mapping.model = kind;
  request.cv_folds = cv;
  request.unit = unit;
  request.memory_limit_gb = memory_limit.value_or(0.0);
  request.mapping.common.seed = seed;
  floorgrid::CrossValidationOptions& folds = request.mapping.auto_select.cv;
  folds.kind = floorgrid::parse_cv_kind(cv_kind, "cv_kind");
  if (!(cv_block >= 0.0 && cv_block <= floorgrid::kMaxCoordinate))
    throw InputError("must be 0 (chosen from the pairs) or a size in metres", {}, 0, "cv_block");
  folds.block_size = cv_block;
  if (budget) {
    if (*budget < 3 || *budget > 10'000'000)
      throw InputError("must be in [3, 10000000]", {}, 0, "budget");
    request.mapping.common.reduction.budget = static_cast<std::size_t>(*budget);
  }
  if (extrapolation)
    request.mapping.common.extrapolation_distance = *extrapolation;
  if (max_error)
    request.mapping.common.max_error = *max_error;
  if (inlier_threshold)
    request.mapping.ransac.inlier_threshold = *inlier_threshold;
  floorgrid::validate(request.mapping.common);
  const floorgrid::ReferencePairs pairs = pairs_from_array(array, unit);
  py::gil_scoped_release release;
  return floorgrid::Model::fit(pairs, request, "pairs");
}

/// The main job with the GIL released; the progress callback runs with it held. A Python
/// exception in the callback (KeyboardInterrupt from Ctrl-C too) stops the job and is raised.
py::dict run_align(floorgrid::Dataset& dataset, const std::string& out,
                   const std::optional<py::function>& progress) {
  std::exception_ptr python_error;
  floorgrid::AlignOptions options;
  options.out = out;
  options.progress = [&](const floorgrid::Progress& p) {
    py::gil_scoped_acquire acquire;
    try {
      if (PyErr_CheckSignals() != 0)
        throw py::error_already_set();
      if (progress)
        (*progress)(p.stage, p.detail, p.done, p.total);
    } catch (py::error_already_set&) {
      python_error = std::current_exception();
      throw floorgrid::Cancelled("align stopped by the progress callback");
    }
  };
  std::optional<floorgrid::AlignResult> result;
  try {
    py::gil_scoped_release release;
    result = floorgrid::align(dataset, options);
  } catch (const floorgrid::Cancelled&) {
    if (python_error)
      std::rethrow_exception(python_error);
    throw;
  }
  py::list models;
  for (std::size_t k = 0; k < result->models.size(); ++k)
    models.append(py::make_tuple(result->model_names[k], result->models[k]));
  return py::dict("pairs"_a = pairs_array(result->pairs), "metrics_json"_a = result->metrics_json,
                  "models"_a = models, "chosen"_a = result->chosen, "files"_a = result->files);
}

}  // namespace

PYBIND11_MODULE(_floorgrid, m) {
  m.doc() = "floorgrid's compiled core; use the `floorgrid` package, which documents it.";

  // InputError(ValueError) carries where the bad input is: file, line, field, message. Messages
  // may quote the bytes of a damaged file: decoded with replacement, never a UnicodeDecodeError.
  static py::exception<floorgrid::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<floorgrid::AlignmentFailure> alignment_failure(m, "AlignmentFailure",
                                                                      PyExc_RuntimeError);
  static py::exception<floorgrid::Cancelled> cancelled(m, "Cancelled", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p)
        std::rethrow_exception(p);
    } catch (const floorgrid::InputError& e) {
      py::object error = py::reinterpret_borrow<py::object>(input_error)(text(e.what()));
      error.attr("file") = e.file().empty() ? py::object(py::none()) : path_text(e.file());
      error.attr("line") = e.line() > 0 ? py::object(py::int_(e.line())) : py::none();
      error.attr("field") = e.field().empty() ? py::object(py::none()) : text(e.field());
      error.attr("message") = text(e.message());
      PyErr_SetObject(input_error.ptr(), error.ptr());
    } catch (const floorgrid::AlignmentFailure& e) {
      PyErr_SetObject(alignment_failure.ptr(), text(e.what()).ptr());
    } catch (const floorgrid::Cancelled& e) {
      PyErr_SetObject(cancelled.ptr(), text(e.what()).ptr());
    }
  });

  m.def("version", &floorgrid::version);
  m.def("options_json", &floorgrid::options_json);
  m.attr("FLAG_NAMES") =
      py::make_tuple("ok", "uncertain", "extrapolated", "outside_hull", "not_invertible");

  py::class_<floorgrid::Model>(m, "Model")
      .def_static("load", &floorgrid::Model::load, "path"_a, "max_error"_a = 0.0,
                  py::call_guard<py::gil_scoped_release>())
      .def_static("fit", &fit_model, "pairs"_a, "kind"_a, "cv"_a, "cv_kind"_a, "cv_block"_a,
                  "unit"_a, "seed"_a, "budget"_a, "extrapolation"_a, "max_error"_a,
                  "inlier_threshold"_a, "memory_limit"_a)
      .def("save", &floorgrid::Model::save, "path"_a, py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("name", &floorgrid::Model::name)
      .def_property_readonly("chosen", &floorgrid::Model::chosen)
      .def_property_readonly("unit", &floorgrid::Model::unit)
      .def_property_readonly("extrapolation_distance", &floorgrid::Model::extrapolation_distance)
      .def_property("max_error", &floorgrid::Model::max_error, &floorgrid::Model::set_max_error)
      .def("summary_json", &floorgrid::Model::summary_json)
      .def("map", &map_points, "points"_a, "inverse"_a);

  py::class_<floorgrid::Dataset>(m, "Dataset")
      .def_static(
          "load",
          [](const std::string& path, const std::optional<std::string>& config,
             const std::optional<std::string>& options_text, std::optional<std::uint64_t> seed,
             std::optional<int> cv, std::optional<std::string> cv_kind,
             std::optional<double> cv_block, std::optional<double> memory_limit,
             std::optional<std::string> pairs_from) {
            const floorgrid::io::JobOverrides o =
                overrides(config, options_text, seed, cv, std::move(cv_kind), cv_block,
                          memory_limit, std::move(pairs_from));
            py::gil_scoped_release release;
            return floorgrid::Dataset::load(path, o);
          },
          "path"_a, "config"_a, "options_text"_a, "seed"_a, "cv"_a, "cv_kind"_a, "cv_block"_a,
          "memory_limit"_a, "pairs_from"_a)
      .def_property_readonly("name", &floorgrid::Dataset::name)
      .def_property_readonly("manifest_path", &floorgrid::Dataset::manifest_path)
      .def_property_readonly("scans", &floorgrid::Dataset::scans)
      .def_property_readonly("has_truth", &floorgrid::Dataset::has_truth);

  m.def("align", &run_align, "dataset"_a, "out"_a, "progress"_a);
}
