#pragma once
// Where the sample's data come from: mineral library, custom indices, thin-section files, the
// mounting medium. Shared by validation (core/io) and the optical set-up, so that both agree on
// what is a known name.
#include <optional>
#include <string>

#include "core/base/asset_locator.h"  // asset_dir(), which the section lookup uses
#include "core/crystal/crystal.h"
#include "core/microscope/scene.h"

namespace pmsim {

bool mineral_known(const std::string& name);
std::string known_minerals_list();  // "augite, biotite, ...; aliases: cpx = augite, ..." for error messages
// Why a mineral name is refused, as the library words it: an unknown name (listing the known ones
// and the aliases), a composition of a mineral that is no series, or a bad composition
// ("plagioclase:An140" is outside 0..100 mol %, "olivine:Xy3" is not written Fo or Fa).
// nullopt when the name is good.
std::optional<std::string> mineral_name_problem(const std::string& name);
bool medium_known(const std::string& name);
// A thin-section name ("granite") or path ("…/granite.json") that resolves to a readable file.
bool section_known(const std::string& name);
// The file a section name refers to: a path as given if it exists, else
// <assets>/sections/<name>[.json], else <assets>/ebsd/<name> (shipped EBSD maps); <assets> is
// $PMSIM_ASSETS or the source tree's assets/.
std::string section_path(const std::string& name);

// The crystal a plate or wedge scene shows: sample.crystal when set (owned by `storage`), else the
// named mineral.
const Crystal& scene_crystal(const Scene& scene, Crystal& storage);

}  // namespace pmsim
