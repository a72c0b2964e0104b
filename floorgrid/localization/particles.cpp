#include "floorgrid/localization/particles.hpp"

namespace floorgrid {

void ParticleSet::resize(std::size_t n) {
  x.resize(n);
  y.resize(n);
  theta.resize(n);
  if (!scale.empty())
    scale.resize(n);
  if (!weight.empty())
    weight.resize(n);
}

}  // namespace floorgrid
