#include "core/base/asset_names.h"

#include "core/base/input_error.h"
#include "core/base/text.h"

namespace pmsim {

void AssetNames::add(const std::string& name, const std::string& file) {
  const auto [it, inserted] = file_of_.emplace(lower_case(name), file);
  if (!inserted)
    throw InputError(file, "name", name, "a " + kind_ + " of this name is already defined in " + it->second);
}

}  // namespace pmsim
