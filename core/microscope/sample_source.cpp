#include "core/microscope/sample_source.h"
#include "core/texture/rock_recipe.h"

#include <filesystem>

#include "core/base/asset_locator.h"
#include "core/base/input_error.h"
#include "core/materials/medium.h"

namespace pmsim {

bool mineral_known(const std::string& name) {
  try {
    find_mineral(name);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

std::string known_minerals_list() { return known_minerals_text(); }

std::optional<std::string> mineral_name_problem(const std::string& name) {
  try {
    canonical_mineral_name(name);
    return std::nullopt;
  } catch (const InputError& e) {
    return e.reason;
  }
}

bool medium_known(const std::string& name) {
  try {
    find_medium(name);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

std::string section_path(const std::string& name) {
  namespace fs = std::filesystem;
  if (name.empty()) return "";
  std::error_code ec;
  if (fs::is_regular_file(name, ec)) return name;
  const fs::path dir = fs::path(asset_dir()) / "sections";
  for (const fs::path& p : {dir / name, dir / (name + ".json")})
    if (fs::is_regular_file(p, ec)) return p.string();
  // EBSD maps the project ships (assets/ebsd/*.ctf, *.ang) by file name.
  if (const fs::path p = fs::path(asset_dir()) / "ebsd" / name; fs::is_regular_file(p, ec)) return p.string();
  return "";
}

bool section_known(const std::string& name) { return !section_path(name).empty() || !rock_recipe_path(name).empty(); }

const Crystal& scene_crystal(const Scene& scene, Crystal& storage) {
  if (scene.sample.crystal) {
    try {
      storage = crystal_from_indices(*scene.sample.crystal);
    } catch (const InputError& e) {
      throw e.under("sample.crystal");
    }
    return storage;
  }
  try {
    return find_mineral(scene.sample.mineral);
  } catch (const InputError& e) {
    throw e.under("sample.mineral");
  }
}

}  // namespace pmsim
