#pragma once

// The two building layouts behind generate_building (internal to simulation/).

#include "floorgrid/core/random.hpp"
#include "floorgrid/simulation/building.hpp"

namespace floorgrid {

/// An office floor of about 40 x 20 m: rows of rooms along one or two corridors.
Building make_office(Random& random);

/// A warehouse hall of about 100 x 50 m: rack rows with aisles and a few offices.
Building make_warehouse(Random& random);

}  // namespace floorgrid
