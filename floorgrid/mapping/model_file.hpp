#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <string>

#include "floorgrid/core/value.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

/// The model file's format name and the version this build writes and reads.
inline constexpr const char* kModelFormat = "floorgrid-model";
inline constexpr int kModelVersion = 1;

/// Rebuilds a fitted model from a model file's values: checks the format, the version and the
/// model name, creates the model and restores it. A model file is a trust boundary (files are
/// passed around and edited): every field is checked for its type, range and finiteness, and
/// sizes against each other, so that no file can make a model crash, hang or allocate without
/// bound. InputError naming `where` (the file) and the field otherwise.
/// `options` are the models' settings the file does not hold (the file's own win), and limits
/// on what loading may derive (options.gp.prediction.lattice.max_nodes caps a GP's lattice).
std::unique_ptr<PointMapping> load_mapping(const Value& model_file, const std::string& where,
                                           const MappingOptions& options);
/// load_mapping with the default options.
std::unique_ptr<PointMapping> load_mapping(const Value& model_file, const std::string& where);

/// Readers and writers of model parameters, each reader throwing InputError naming `where` and
/// `field` (a dotted path, "parameters.T_grid_plan").
namespace model_fields {

/// Points a model file may hold in one list at most (a model keeps at most a few ten thousand).
inline constexpr std::size_t kMaxPoints = 10'000'000;

/// A 2 x N matrix as [[x, y], ...].
Value points(const Eigen::Matrix2Xd& points);
/// Reads [[x, y], ...]: finite coordinates within kMaxCoordinate metres, at most kMaxPoints.
Eigen::Matrix2Xd points(const Value& v, const std::string& where, const std::string& field);
/// Reads [[x, y], ...] of finite numbers of any size (weights, not coordinates).
Eigen::Matrix2Xd number_pairs(const Value& v, const std::string& where, const std::string& field);
/// A matrix as nested rows.
Value matrix(const Eigen::MatrixXd& m);
/// Reads nested rows of exactly `rows` x `cols` finite numbers.
Eigen::MatrixXd matrix(const Value& v, const std::string& where, const std::string& field,
                       Eigen::Index rows, Eigen::Index cols);
/// A vector as a list.
Value vector(const Eigen::VectorXd& v);
/// Reads a list of finite numbers (exactly `size` of them when size > 0).
Eigen::VectorXd vector(const Value& v, const std::string& where, const std::string& field,
                       Eigen::Index size = 0);
/// Reads a finite number in [lo, hi].
double number(const Value& v, const std::string& where, const std::string& field,
              double lo = -1e300, double hi = 1e300);
/// Reads a whole number in [lo, hi].
std::int64_t integer(const Value& v, const std::string& where, const std::string& field,
                     std::int64_t lo, std::int64_t hi);
/// Reads true or false.
bool flag(const Value& v, const std::string& where, const std::string& field);
/// Reads a text.
const std::string& text(const Value& v, const std::string& where, const std::string& field);
/// The member `key` of an object (field `prefix` + key).
const Value& member(const Value& v, const std::string& key, const std::string& where,
                    const std::string& prefix = {});
/// The member `key` when present and not null, else nullptr.
const Value* optional_member(const Value& v, const std::string& key);

}  // namespace model_fields

}  // namespace floorgrid
