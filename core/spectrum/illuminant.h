#pragma once
// CIE standard illuminants (CIE 15:2004, Table T.1): relative spectral power, 300–830 nm data,
// used here over the visible range 380–780 nm.
#include <string_view>

namespace pmsim {

enum class Illuminant { D65, A };

// Relative spectral power distribution S(λ), normalised to 100 at 560 nm (CIE convention).
// Linear interpolation between table entries; outside 380–780 nm throws std::out_of_range.
double illuminant_spd(Illuminant illum, double wavelength_nm);

std::string_view illuminant_name(Illuminant illum);  // "D65", "A"
// Parses "D65"/"A" (case-insensitive); returns false on an unknown name.
bool parse_illuminant(std::string_view name, Illuminant& out);

}  // namespace pmsim
