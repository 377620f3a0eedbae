#include "core/crystal/lattice.h"

#include <cctype>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "core/base/json_reader.h"
#include "core/base/units.h"

namespace pmsim {

namespace {

// cos and sin of an angle typed in degrees, exact for the right angles and 120° that most cells
// have, so that orthogonal cells give axes without 1e-17 residues (a cut along them then equals the
// same axes typed as vectors, bit for bit).
double cos_deg(double d) {
  if (d == 90.0) return 0.0;
  if (d == 120.0) return -0.5;
  if (d == 60.0) return 0.5;
  return std::cos(radians(d));
}
double sin_deg(double d) {
  if (d == 90.0) return 1.0;
  if (d == 120.0 || d == 60.0) return std::sqrt(3.0) / 2.0;
  return std::sin(radians(d));
}

bool same(double x, double y) { return std::abs(x - y) <= 1e-9 * std::max(std::abs(x), std::abs(y)); }

std::string num(double v) { return number_text(v); }

// Indices between the brackets: separated ("1 -1 0", "1,0,12") or written together ("1-10").
std::vector<int> indices(std::string_view text, char open, char close, const char* what) {
  const std::string example = open == '(' ? "\"(1-10)\"" : "\"[-101]\"";
  if (text.size() < 2 || text.front() != open || text.back() != close)
    throw BadValue{std::string("expected ") + what + " like " + example};
  const std::string_view body = text.substr(1, text.size() - 2);
  const bool separated = body.find_first_of(" ,") != std::string_view::npos;
  std::vector<int> r;
  std::size_t i = 0;
  while (i < body.size()) {
    if (body[i] == ' ' || body[i] == ',') {
      ++i;
      continue;
    }
    int sign = 1;
    if (body[i] == '-') sign = -1, ++i;
    if (i >= body.size() || !std::isdigit(static_cast<unsigned char>(body[i])))
      throw BadValue{std::string("expected ") + what + " like " + example +
                     " (integer indices, a minus sign before a negative one)"};
    int v = 0;
    do {
      v = v * 10 + (body[i] - '0');
      ++i;
      if (v > 99) throw BadValue{"indices beyond 99 are no crystal face or zone"};
    } while (separated && i < body.size() && std::isdigit(static_cast<unsigned char>(body[i])));
    r.push_back(sign * v);
  }
  if (r.size() != 3 && r.size() != 4)
    throw BadValue{std::string("expected three indices (or four, Miller–Bravais) in ") + what + " like " +
                   example};
  bool zero = true;
  for (int v : r) zero &= v == 0;
  if (zero) throw BadValue{"all indices zero define no plane or direction"};
  return r;
}

}  // namespace

const char* crystal_system_name(CrystalSystem s) {
  switch (s) {
    case CrystalSystem::Cubic:
      return "cubic";
    case CrystalSystem::Tetragonal:
      return "tetragonal";
    case CrystalSystem::Hexagonal:
      return "hexagonal";
    case CrystalSystem::Trigonal:
      return "trigonal";
    case CrystalSystem::Orthorhombic:
      return "orthorhombic";
    case CrystalSystem::Monoclinic:
      return "monoclinic";
    case CrystalSystem::Triclinic:
      return "triclinic";
  }
  return "triclinic";
}

void check_unit_cell(CrystalSystem system, const UnitCell& c) {
  for (double e : {c.a_A, c.b_A, c.c_A})
    if (!(std::isfinite(e) && e > 0.0 && e < 1000.0)) throw BadValue{"cell edges must be in (0, 1000) Å"};
  for (double g : {c.alpha_deg, c.beta_deg, c.gamma_deg})
    if (!(std::isfinite(g) && g > 0.0 && g < 180.0)) throw BadValue{"cell angles must be in (0, 180)°"};
  const double ca = cos_deg(c.alpha_deg), cb = cos_deg(c.beta_deg), cg = cos_deg(c.gamma_deg);
  // V² = a²b²c²(1 − cos²α − cos²β − cos²γ + 2 cos α cos β cos γ) must be positive.
  if (!(1 - ca * ca - cb * cb - cg * cg + 2 * ca * cb * cg > 1e-12))
    throw BadValue{"the cell angles " + num(c.alpha_deg) + ", " + num(c.beta_deg) + ", " + num(c.gamma_deg) +
                   "° enclose no volume"};
  auto need = [&](bool ok, const char* rule) {
    if (!ok) throw BadValue{std::string(crystal_system_name(system)) + " cells have " + rule};
  };
  const bool right_a = c.alpha_deg == 90, right_b = c.beta_deg == 90, right_g = c.gamma_deg == 90;
  switch (system) {
    case CrystalSystem::Cubic:
      need(same(c.a_A, c.b_A) && same(c.b_A, c.c_A) && right_a && right_b && right_g,
           "a = b = c, α = β = γ = 90°");
      break;
    case CrystalSystem::Tetragonal:
      need(same(c.a_A, c.b_A) && right_a && right_b && right_g, "a = b, α = β = γ = 90°");
      break;
    case CrystalSystem::Hexagonal:
    case CrystalSystem::Trigonal:
      need(same(c.a_A, c.b_A) && right_a && right_b && c.gamma_deg == 120,
           "a = b, α = β = 90°, γ = 120° (hexagonal setting)");
      break;
    case CrystalSystem::Orthorhombic:
      need(right_a && right_b && right_g, "α = β = γ = 90°");
      break;
    case CrystalSystem::Monoclinic:
      need(right_a && right_g && !right_b, "α = γ = 90° and β ≠ 90° (b unique)");
      break;
    case CrystalSystem::Triclinic:
      break;
  }
}

glm::dmat3 direct_basis(const UnitCell& c) {
  const double ca = cos_deg(c.alpha_deg), cb = cos_deg(c.beta_deg), cg = cos_deg(c.gamma_deg);
  const double sg = sin_deg(c.gamma_deg);
  const glm::dvec3 a(c.a_A, 0, 0);
  const glm::dvec3 b(c.b_A * cg, c.b_A * sg, 0);
  const double cx = c.c_A * cb;
  const double cy = c.c_A * (ca - cb * cg) / sg;
  const double cz = std::sqrt(std::max(0.0, c.c_A * c.c_A - cx * cx - cy * cy));
  return glm::dmat3(a, b, glm::dvec3(cx, cy, cz));
}

glm::dmat3 reciprocal_basis(const UnitCell& cell) {
  const glm::dmat3 d = direct_basis(cell);
  const double V = glm::dot(d[0], glm::cross(d[1], d[2]));
  return glm::dmat3(glm::cross(d[1], d[2]) / V, glm::cross(d[2], d[0]) / V, glm::cross(d[0], d[1]) / V);
}

glm::dvec3 plane_normal(const UnitCell& cell, MillerIndices p) {
  const glm::dmat3 r = reciprocal_basis(cell);
  return glm::normalize(double(p.h) * r[0] + double(p.k) * r[1] + double(p.l) * r[2]);
}

glm::dvec3 lattice_direction(const UnitCell& cell, LatticeDirection d) {
  const glm::dmat3 m = direct_basis(cell);
  return glm::normalize(double(d.u) * m[0] + double(d.v) * m[1] + double(d.w) * m[2]);
}

MillerIndices parse_miller_plane(std::string_view text) {
  const auto v = indices(text, '(', ')', "a plane");
  if (v.size() == 4) {
    if (v[2] != -(v[0] + v[1])) throw BadValue{"in (hkil) the third index must be i = −(h + k)"};
    return {v[0], v[1], v[3]};
  }
  return {v[0], v[1], v[2]};
}

LatticeDirection parse_lattice_direction(std::string_view text) {
  const auto v = indices(text, '[', ']', "a direction");
  if (v.size() == 4) {
    if (v[2] != -(v[0] + v[1])) throw BadValue{"in [UVTW] the third index must be T = −(U + V)"};
    return {2 * v[0] + v[1], v[0] + 2 * v[1], v[3]};
  }
  return {v[0], v[1], v[2]};
}

namespace {
std::string joined(std::array<int, 3> v) {
  bool wide = false;
  for (int x : v) wide |= std::abs(x) > 9;
  std::string s;
  for (int i = 0; i < 3; ++i) {
    if (wide && i) s += ' ';
    s += std::to_string(v[i]);
  }
  return s;
}
}  // namespace

// Appended rather than "(" + …: GCC 12 warns falsely (-Wrestrict) on a literal + std::string.
std::string miller_text(MillerIndices p) { return std::string(1, '(').append(joined({p.h, p.k, p.l})).append(1, ')'); }
std::string direction_text(LatticeDirection d) {
  return std::string(1, '[').append(joined({d.u, d.v, d.w})).append(1, ']');
}

}  // namespace pmsim
