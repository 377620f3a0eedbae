#pragma once
// Linear interpolation in the 380–780 nm, 5 nm CIE tables (internal to core/spectrum).
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/spectrum/cie_tables.h"

namespace pmsim::detail {

// Index of the table interval holding wavelength_nm and the fraction within it; throws
// std::out_of_range (naming the caller) outside [380, 780] nm or for NaN.
inline void visible_table_position(double wavelength_nm, const char* who, int& index, double& fraction) {
  using namespace cie_tables;
  constexpr double last_nm = kFirstNm + kStepNm * (kCount - 1);
  if (!(wavelength_nm >= kFirstNm && wavelength_nm <= last_nm)) {
    throw std::out_of_range(std::string(who) + ": wavelength " + std::to_string(wavelength_nm) +
                            " nm outside the tabulated 380-780 nm");
  }
  const double x = (wavelength_nm - kFirstNm) / kStepNm;
  index = static_cast<int>(x);
  if (index >= kCount - 1) index = kCount - 2;
  fraction = x - index;
}

inline double lookup_visible_table(const double* table, double wavelength_nm, const char* who) {
  int i = 0;
  double f = 0.0;
  visible_table_position(wavelength_nm, who, i, f);
  return table[i] + f * (table[i + 1] - table[i]);
}

}  // namespace pmsim::detail
