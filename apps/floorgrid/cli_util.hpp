#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"

namespace floorgrid::app {

/// Checks a `--seed` value before CLI11 converts it: a whole number from 0 to 2^64 - 1 (CLI11
/// alone reads -1 as 2^64 - 1 and so does not refuse it).
CLI::Validator seed_check();

/// Parses "a,b,c" into numbers; throws InputError naming `option` when a part is not a finite
/// number or the count is not one of `counts`.
std::vector<double> parse_numbers(const std::string& text, const std::string& option,
                                  const std::vector<std::size_t>& counts);

/// Parses "x,y,yaw" (or "x,y" with yaw 0) into a pose; throws InputError naming `option`.
Pose2 parse_pose(const std::string& text, const std::string& option);

/// Refuses an output that would overwrite an input (the same file, however it is named):
/// InputError naming `option`.
void refuse_overwriting_input(const std::string& input, const std::string& output,
                              const std::string& option);

/// Writes report.html from `out`'s files and says where it is; a failure costs the report (a
/// warning), not the job.
void write_report(const std::filesystem::path& out);

}  // namespace floorgrid::app
