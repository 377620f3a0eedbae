#pragma once
// An immersion liquid of a refractive-index series (grain mounts): n_D as ordered, and the series'
// dispersion n_F − n_C at that n_D (assets/liquids/immersion_liquids.json, measured calibration
// liquids; interpolated in n_D, extrapolated at constant Abbe number beyond them).
// n(λ) is the two-term Cauchy curve A + B/λ² through n_D (589.26 nm) and n_F − n_C (486.13,
// 656.28 nm): B = (n_F − n_C)/(λ_F⁻² − λ_C⁻²), A = n_D − B/λ_D².
#include <string>

namespace pmsim {

struct ImmersionLiquid {
  double nd = 1.54;
  double nf_minus_nc = 0.0;
  double A = 1.54, B_nm2 = 0.0;
  double n(double wavelength_nm) const;
  double abbe_vd() const { return nf_minus_nc > 0.0 ? (nd - 1.0) / nf_minus_nc : 0.0; }
};

// The liquid of the series with this n_D (1.40…1.80: the scene check's range; outside it
// std::invalid_argument). Loads the series file once; InputError naming file and key if it is bad.
ImmersionLiquid immersion_liquid(double nd);
// A liquid with exactly this n_D and n_F − n_C (tests, other series).
ImmersionLiquid immersion_liquid(double nd, double nf_minus_nc);

}  // namespace pmsim
