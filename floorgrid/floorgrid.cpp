#include "floorgrid/floorgrid.hpp"

#include <cmath>
#include <limits>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/system_memory.hpp"
#include "floorgrid/io/files/value_json.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/formats/points_csv.hpp"
#include "floorgrid/io/jobs/alignment_job.hpp"
#include "floorgrid/io/options/options_schema.hpp"

namespace floorgrid {

std::string version() {
  return FLOORGRID_VERSION;
}

std::string options_json() {
  JobOptions defaults;
  return io::options_json(io::job_option_tree(defaults));
}

// ---- Model ----

Model::Model(std::shared_ptr<PointMapping> mapping) : mapping_(std::move(mapping)) {
  if (!mapping_ || !mapping_->fitted())
    throw std::invalid_argument("floorgrid::Model needs a fitted mapping");
}

Model Model::load(const std::string& path, double max_error_m) {
  std::shared_ptr<PointMapping> mapping = io::read_model(path);
  if (max_error_m > 0.0)
    mapping->set_max_error(max_error_m);
  return Model(std::move(mapping));
}

Model Model::fit(const ReferencePairs& pairs, ModelFitRequest request, const std::string& source) {
  if (!(request.memory_limit_gb > 0.0))
    request.memory_limit_gb = io::default_memory_limit_gb();  // as `floorgrid fit`
  return Model(fit_checked(pairs, request, source).model);
}

void Model::save(const std::string& path) const {
  io::write_model(*mapping_, path);
}

std::string Model::name() const {
  return mapping_->name();
}

std::string Model::chosen() const {
  const Value* chosen = mapping_->summary().details.find("chosen");
  return chosen && chosen->is_string() ? chosen->as_string() : name();
}

double Model::unit() const {
  return mapping_->unit();
}

double Model::extrapolation_distance() const {
  return mapping_->common().extrapolation_distance;
}

double Model::max_error() const {
  return mapping_->common().max_error;
}

void Model::set_max_error(double metres) {
  mapping_->set_max_error(metres);
}

std::string Model::summary_json() const {
  const Value file = mapping_->to_model_file();
  Value summary = Value::object();
  if (const Value* fit = file.find("fit"))
    summary = *fit;
  if (const Value* pairs = file.find("pairs"))
    summary["pairs"] = *pairs;
  return io::dump_json(summary, -1);
}

void Model::map(const Eigen::Ref<const Eigen::MatrixXd>& in, bool inverse,
                Eigen::Ref<Eigen::MatrixXd> out, Eigen::Ref<Eigen::VectorXd> std_m,
                Eigen::Ref<Eigen::VectorXd> nearest_pair_m,
                Eigen::Ref<Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1>> flags) const {
  const Eigen::Index n = in.cols();
  if ((in.rows() != 2 && in.rows() != 3) || out.rows() != in.rows() || out.cols() != n ||
      std_m.size() != n || nearest_pair_m.size() != n || flags.size() != n)
    throw std::invalid_argument("Model::map: points are 2 x N or poses 3 x N, outputs of N");
  const bool poses = in.rows() == 3;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Coordinates beyond kMaxCoordinate metres are not physical (as `map` refuses them): their
  // rows are not_invertible, with no number.
  const double max_abs = kMaxCoordinate / mapping_->unit();
  // Rows are independent and models are immutable once loaded: two threads share them.
  parallel_chunks(
      static_cast<std::size_t>(n), 4096, kDefaultThreads, [&](std::size_t begin, std::size_t end) {
        for (auto i = static_cast<Eigen::Index>(begin); i < static_cast<Eigen::Index>(end); ++i) {
          const Eigen::Vector2d point(in(0, i), in(1, i));
          if (!(std::abs(point.x()) <= max_abs && std::abs(point.y()) <= max_abs)) {
            out.col(i).setConstant(nan);
            std_m[i] = nan;
            nearest_pair_m[i] = nan;
            flags[i] = static_cast<std::uint8_t>(MapFlag::not_invertible);
            continue;
          }
          const double theta = poses ? in(2, i) : 0.0;
          const double* heading = poses ? &theta : nullptr;
          const io::MappedRow row = io::map_row(*mapping_, point, heading, inverse);
          out(0, i) = row.mapped.point.x();
          out(1, i) = row.mapped.point.y();
          if (poses)
            out(2, i) = row.heading ? *row.heading : nan;
          std_m[i] = row.mapped.std_m ? *row.mapped.std_m : nan;
          nearest_pair_m[i] = row.mapped.nearest_pair_m;
          flags[i] = static_cast<std::uint8_t>(row.mapped.flag);
        }
      });
}

namespace {

MappedPoints map_all(const Model& model, const Eigen::Ref<const Eigen::MatrixXd>& in,
                     bool inverse) {
  MappedPoints m;
  m.values.resize(in.rows(), in.cols());
  m.std_m.resize(in.cols());
  m.nearest_pair_m.resize(in.cols());
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1> flags(in.cols());
  model.map(in, inverse, m.values, m.std_m, m.nearest_pair_m, flags);
  m.flags.reserve(static_cast<std::size_t>(flags.size()));
  for (const std::uint8_t f : flags)
    m.flags.push_back(static_cast<MapFlag>(f));
  return m;
}

}  // namespace

MappedPoints Model::forward(const Eigen::Ref<const Eigen::MatrixXd>& in_plan) const {
  return map_all(*this, in_plan, false);
}

MappedPoints Model::inverse(const Eigen::Ref<const Eigen::MatrixXd>& in_grid) const {
  return map_all(*this, in_grid, true);
}

// ---- Dataset ----

Dataset Dataset::load(const std::string& path, const io::JobOverrides& options) {
  Dataset d;
  d.options_ = options;
  d.job_ = io::load_alignment_job(path, io::job_options(options));
  return d;
}

Dataset::~Dataset() = default;
Dataset::Dataset(Dataset&&) noexcept = default;
Dataset& Dataset::operator=(Dataset&&) noexcept = default;

std::string Dataset::name() const {
  return job_->dataset.manifest.display_name();
}

std::string Dataset::manifest_path() const {
  return job_->dataset.manifest.manifest_path.string();
}

std::size_t Dataset::scans() const {
  return job_->dataset.log ? job_->dataset.log->scans.size() : 0;
}

bool Dataset::has_truth() const {
  return job_->dataset.truth_warp || job_->dataset.manual_pairs;
}

// ---- align ----

const Model& AlignResult::model(const std::string& name) const {
  for (std::size_t k = 0; k < model_names.size(); ++k) {
    if (model_names[k] == name)
      return models[k];
  }
  throw InputError("no model of this name was fitted", {}, 0, name);
}

AlignResult align(Dataset& dataset, const AlignOptions& options) {
  const JobOptions job_options = io::job_options(dataset.options());
  io::AlignmentJob& job = dataset.job();
  // Made before the work (a folder that cannot be made fails at once), removed again when the
  // job fails before writing into it, as `floorgrid align` does.
  std::optional<io::OutputFolder> out_folder;
  if (!options.out.empty())
    out_folder.emplace(options.out);
  Alignment a = io::run_alignment_job(job, job_options, [&](const AlignmentProgress& p) {
    if (options.cancel && options.cancel->load())
      throw Cancelled("align cancelled");
    if (options.progress)
      options.progress({p.stage, p.detail, p.done, p.total});
  });
  AlignResult result;
  std::string failure;
  nlohmann::json metrics;
  if (!options.out.empty()) {
    const io::AlignmentFolder folder = io::write_alignment_folder(job, a, job_options, options.out);
    for (const std::filesystem::path& file : folder.files.files)
      result.files.push_back(file.string());
    if (folder.exports) {
      for (const std::filesystem::path& file : folder.exports->files)
        result.files.push_back((std::filesystem::path("exports") / file).string());
    }
    if (folder.report)
      result.files.push_back("report.html");
    failure = folder.failure;
    metrics = folder.files.metrics;
  } else {
    metrics = io::alignment_metrics(job, a);
  }
  if (!failure.empty())
    throw AlignmentFailure(failure);
  result.metrics_json = metrics.dump(1);
  result.pairs = a.localization.pairs;
  result.chosen = a.chosen;
  for (ModelAlignment& m : a.models) {
    if (!m.report.model)
      continue;
    result.model_names.push_back(m.report.name);
    result.models.emplace_back(std::shared_ptr<PointMapping>(std::move(m.report.model)));
  }
  return result;
}

AlignResult align(const std::string& dataset, const AlignOptions& options) {
  Dataset d = Dataset::load(dataset, options.job);
  return align(d, options);
}

}  // namespace floorgrid
