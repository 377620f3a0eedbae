#pragma once
// Which library mineral an EBSD phase is, from the name the map file gives it.
//
// Resolution, first match wins:
//  1. `explicit_map` (the scene's sample.phases = {"<name in the file>": "<mineral>", …}): the
//     key equal to the file's name, else equal ignoring ASCII case and surrounding blanks. The
//     value is a library mineral, an alias of the table below, a composition ("olivine:Fo90":
//     the part before ':' must be a library mineral; the composition is the mineral library's to
//     check), "isotropic" or "none".
//  2. The name itself, ignoring case, surrounding blanks and '_' for ' ': "isotropic"/"none", an
//     entry of assets/ebsd/phase_names.json (aliases such as Garnet, Opx, Clinopyroxene,
//     Forsterite, each with its rationale), or a library mineral name.
//  3. The same after removing the qualifiers EBSD phase databases add to names: suffixes "-new",
//     " new", " low", "-low", " high", "-high", " alpha", "-alpha" and prefixes "low ", "high ",
//     "alpha-", "alpha " ("Quartz-new", "Quartz low", "Low albite").
// A name that resolves to nothing is bad input: InputError naming the phase as the file spells
// it and how to map it (key "sample.phases"; `file` is the scene or map file to name).
#include <map>
#include <string>

namespace pmsim {

// "isotropic", "none", a library mineral name (lower case) or an explicit map's value as written.
std::string map_phase_name(const std::string& name_in_file, const std::map<std::string, std::string>& explicit_map,
                           const std::string& file = "");

}  // namespace pmsim
