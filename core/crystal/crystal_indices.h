#pragma once
// Constant principal refractive indices of a user-defined crystal (a scene's sample.crystal), and
// the index rule every reader of indices applies (scene files, --set, mineral files).
#include <string_view>

namespace pmsim {

struct CrystalIndices {  // {"no":..,"ne":..} or {"nalpha":..,"nbeta":..,"ngamma":..}
  bool uniaxial = true;
  double no = 1.544, ne = 1.553;                   // uniaxial
  double nalpha = 1.5, nbeta = 1.5, ngamma = 1.5;  // biaxial
  bool operator==(const CrystalIndices&) const = default;
};

// n ∈ (1, 5]: below 1 is not a dielectric at optical frequencies; above 5 is no mineral (the
// highest, rutile and cinnabar, stay under 3.3), so such a value is a typo. The check functions
// throw BadValue (core/base/json_reader.h) with the reason; the caller names the key.
bool refractive_index_valid(double n);
void check_refractive_index(double n);  // "a refractive index must be in (1, 5]"
// nα ≤ nβ ≤ nγ (X, Y, Z of the optical-mineralogy convention, Nesse 2012 §7).
void check_biaxial_order(double nalpha, double nbeta, double ngamma);
void check_crystal_indices(const CrystalIndices& c);  // both rules; the reason names the index

}  // namespace pmsim
