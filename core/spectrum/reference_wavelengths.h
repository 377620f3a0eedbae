#pragma once
// The wavelengths that conventions, not spectra, fix: where a table's index is read and what one
// interference order is. Written once here; every renderer, report and panel reads these names.

namespace pmsim {

// n_D of the mineral tables (Nesse 2012, Introduction to Optical Mineralogy; Deer, Howie &
// Zussman 2013): the sodium D doublet's centre, 589.3 nm.
inline constexpr double kMineralTableDNm = 589.3;
// n_D of immersion liquids and mounting media as their reference series gives it
// (assets/liquids/immersion_liquids.json: IUPAC, Marsh 1987, D = 589.26 nm). The 0.04 nm from
// kMineralTableDNm moves an index by ~10⁻⁶, below either source's last digit; each is kept as
// its source states it.
inline constexpr double kLiquidDNm = 589.26;
// One interference order on the Michel-Lévy chart: retardation 550 nm, the first-order red's
// (Nesse 2012 §7.5; Sørensen 2013, Eur. J. Mineral. 25, 5-10).
inline constexpr double kOrderWavelengthNm = 550.0;

}  // namespace pmsim
