#include "floorgrid/mapping/mapping_factory.hpp"

#include "floorgrid/core/error.hpp"

namespace floorgrid {

std::unique_ptr<PointMapping> make_mapping(const MappingOptions& options) {
  validate(options.uncertainty);
  if (const ModelEntry* entry = find_model(options.model))
    return entry->make(options);
  std::string known;
  for (const auto& name : mapping_model_names())
    known += (known.empty() ? "" : ", ") + name;
  throw InputError("unknown model '" + options.model + "' (known: " + known + ")", {}, 0, "model");
}

}  // namespace floorgrid
