// A deliberate break of the dependency rule: check_includes must refuse this tree.
#pragma once

#include "floorgrid/io/map_io.hpp"
#include "floorgrid/mapping/point_mapping.hpp"
#include <nlohmann/json.hpp>
