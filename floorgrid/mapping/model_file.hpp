#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

/// The model file's format name and the version this build writes and reads.
inline constexpr const char* kModelFormat = "floorgrid-model";
inline constexpr int kModelVersion = 1;

/// Rebuilds a fitted model from a model file's JSON: checks the format, the version and the
/// model name, creates the model and restores it. InputError naming `where` and the field for
/// another format, another version, an unknown model or a malformed field.
std::unique_ptr<PointMapping> load_mapping(const nlohmann::json& model_file,
                                           const std::string& where);

/// JSON helpers for model parameters, each throwing InputError naming `where` and `field`.
namespace model_json {
/// A 2 x N matrix as [[x, y], ...].
nlohmann::json points(const Eigen::Matrix2Xd& points);
/// Reads [[x, y], ...].
Eigen::Matrix2Xd points(const nlohmann::json& j, const std::string& where,
                        const std::string& field);
/// A matrix as nested rows.
nlohmann::json matrix(const Eigen::MatrixXd& m);
/// Reads nested rows of the given size (0: any).
Eigen::MatrixXd matrix(const nlohmann::json& j, const std::string& where, const std::string& field,
                       Eigen::Index rows = 0, Eigen::Index cols = 0);
/// A vector as a list.
nlohmann::json vector(const Eigen::VectorXd& v);
/// Reads a list of numbers.
Eigen::VectorXd vector(const nlohmann::json& j, const std::string& where, const std::string& field);
/// A finite number.
double number(const nlohmann::json& j, const std::string& where, const std::string& field);
/// The member `key` of an object.
const nlohmann::json& member(const nlohmann::json& j, const std::string& key,
                             const std::string& where, const std::string& field_prefix = {});
}  // namespace model_json

}  // namespace floorgrid
