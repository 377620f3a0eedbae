#include "core/crystal/crystal_indices.h"

#include <cmath>
#include <string>

#include "core/base/json_reader.h"

namespace pmsim {

bool refractive_index_valid(double n) { return std::isfinite(n) && n > 1.0 && n <= 5.0; }

void check_refractive_index(double n) {
  if (!refractive_index_valid(n)) throw BadValue{"a refractive index must be in (1, 5]"};
}

void check_biaxial_order(double nalpha, double nbeta, double ngamma) {
  if (!(nalpha <= nbeta && nbeta <= ngamma))
    throw BadValue{"biaxial indices must satisfy nalpha ≤ nbeta ≤ ngamma"};
}

void check_crystal_indices(const CrystalIndices& c) {
  auto check = [](double n, const char* name) {
    try {
      check_refractive_index(n);
    } catch (const BadValue& b) {
      throw BadValue{std::string(name) + " = " + number_text(n) + ": " + b.why};
    }
  };
  if (c.uniaxial) {
    check(c.no, "no");
    check(c.ne, "ne");
    return;
  }
  check(c.nalpha, "nalpha");
  check(c.nbeta, "nbeta");
  check(c.ngamma, "ngamma");
  check_biaxial_order(c.nalpha, c.nbeta, c.ngamma);
}

}  // namespace pmsim
