#include "core/spectrum/illuminant.h"

#include <cctype>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/spectrum/cie_tables.h"
#include "core/spectrum/table_lookup.h"

namespace pmsim {

double illuminant_spd(Illuminant illum, double wavelength_nm) {
  const double* table = illum == Illuminant::A ? cie_tables::kA : cie_tables::kD65;
  return detail::lookup_visible_table(table, wavelength_nm, "illuminant_spd");
}

std::string_view illuminant_name(Illuminant illum) {
  switch (illum) {
    case Illuminant::D65:
      return "D65";
    case Illuminant::A:
      return "A";
  }
  return "?";
}

bool parse_illuminant(std::string_view name, Illuminant& out) {
  std::string upper(name);
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (upper == "D65") {
    out = Illuminant::D65;
    return true;
  }
  if (upper == "A") {
    out = Illuminant::A;
    return true;
  }
  return false;
}

}  // namespace pmsim
