// A deliberate break of the dependency rule: check_includes must refuse this tree.
#pragma once

#include <nlohmann/json.hpp>
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/mapping/point_mapping.hpp"
