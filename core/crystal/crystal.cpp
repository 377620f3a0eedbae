// Principal indices with dispersion, pleochroic absorption, rotatory power, orientation helpers
// and the optic angle of a crystal (see crystal.h for the axis conventions).
#include "core/crystal/crystal.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/base/conventions.h"
#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/optics/cauchy.h"

namespace pmsim {

double IndexDispersion::n(double wavelength_nm) const {
  const double l = wavelength_nm * 1e-3;  // µm
  const double l2 = l * l;
  switch (model) {
    case Model::Constant:
      return A;
    case Model::Ghosh1999:
      // Ghosh 1999, Opt. Commun. 163, 95, eq. (3): n² = A + B/(1 − C/λ²) + D/(1 − E/λ²).
      return std::sqrt(A + B / (1.0 - C / l2) + D / (1.0 - E / l2));
    case Model::Cauchy:
      return cauchy_index(A, B, C, l);  // λ in µm
  }
  return A;
}

double AbsorptionTable::mu(double lambda_nm) const {
  if (empty()) return 0.0;
  const auto& w = this->wavelength_nm;
  if (lambda_nm <= w.front()) return mu_per_um.front();
  if (lambda_nm >= w.back()) return mu_per_um.back();
  const auto it = std::upper_bound(w.begin(), w.end(), lambda_nm);
  const size_t i = static_cast<size_t>(it - w.begin());
  const double f = (lambda_nm - w[i - 1]) / (w[i] - w[i - 1]);
  return mu_per_um[i - 1] + f * (mu_per_um[i] - mu_per_um[i - 1]);
}

double RotatoryDispersion::rho(double wavelength_nm) const {
  // Drude's one-term law of rotatory dispersion: ρ = A/(λ² − λ0²) (Lowry, "Optical Rotatory Power", 1935).
  const double l = wavelength_nm * 1e-3;
  return A_rad_um / (l * l - lambda0_um * lambda0_um);
}

Crystal Crystal::make(std::string name, CrystalSymmetry symmetry, IndexDispersion x, IndexDispersion y,
                      IndexDispersion z, std::string source) {
  Crystal c;
  c.name_ = std::move(name);
  c.symmetry_ = symmetry;
  c.disp_[0] = x;
  c.disp_[1] = y;
  c.disp_[2] = z;
  c.constant_ = x.model == IndexDispersion::Model::Constant && y.model == IndexDispersion::Model::Constant &&
                z.model == IndexDispersion::Model::Constant;
  c.constant_indices_ = glm::dvec3(x.A, y.A, z.A);
  c.source_ = std::move(source);
  return c;
}

namespace {
IndexDispersion constant_index(double n) {
  IndexDispersion d;
  d.A = n;
  return d;
}
}  // namespace

Crystal Crystal::uniaxial_constant(std::string name, double no, double ne) {
  return make(std::move(name), CrystalSymmetry::Uniaxial, constant_index(no), constant_index(no),
              constant_index(ne), "constant indices given by the user");
}

Crystal Crystal::biaxial_constant(std::string name, double nalpha, double nbeta, double ngamma) {
  return make(std::move(name), CrystalSymmetry::Biaxial, constant_index(nalpha), constant_index(nbeta),
              constant_index(ngamma), "constant indices given by the user");
}

Crystal Crystal::isotropic_constant(std::string name, double n) {
  return make(std::move(name), CrystalSymmetry::Isotropic, constant_index(n), constant_index(n),
              constant_index(n), "constant index given by the user");
}

glm::dvec3 Crystal::dispersive_indices(double wavelength_nm) const {
  return {disp_[0].n(wavelength_nm), disp_[1].n(wavelength_nm), disp_[2].n(wavelength_nm)};
}

glm::dvec3 Crystal::principal_absorption_per_um(double wavelength_nm) const {
  if (!absorbing_) return glm::dvec3(0.0);
  return {absorption_[0].mu(wavelength_nm), absorption_[1].mu(wavelength_nm),
          absorption_[2].mu(wavelength_nm)};
}

void Crystal::set_absorption(AbsorptionTable x, AbsorptionTable y, AbsorptionTable z) {
  absorption_[0] = std::move(x);
  absorption_[1] = std::move(y);
  absorption_[2] = std::move(z);
  absorbing_ = !(absorption_[0].empty() && absorption_[1].empty() && absorption_[2].empty());
}

Crystal Crystal::with_absorption_scaled(double factor, std::string name) const {
  Crystal c = *this;
  c.name_ = std::move(name);
  for (AbsorptionTable& t : c.absorption_)
    for (double& mu : t.mu_per_um) mu *= factor;
  return c;
}

void Crystal::set_rotatory_power(RotatoryDispersion rho) {
  rotatory_ = rho;
  optically_active_ = rho.A_rad_um != 0.0;
}

namespace {
glm::dvec3 checked_unit(const glm::dvec3& v, const char* what) {
  const double len = glm::length(v);
  if (!(len > 0.0) || !std::isfinite(len))
    throw std::invalid_argument(std::string(what) + " must be a finite non-zero vector");
  return v / len;
}
}  // namespace

glm::dmat3 uniaxial_orientation(glm::dvec3 optic_axis) {
  const glm::dvec3 z = checked_unit(optic_axis, "optic_axis");
  // Any X ⟂ Z serves (X and Y are equivalent in a uniaxial crystal); take the one nearest lab x.
  glm::dvec3 ref = std::abs(z.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 x = glm::normalize(ref - glm::dot(ref, z) * z);
  const glm::dvec3 y = glm::cross(z, x);
  return glm::dmat3(x, y, z);
}

glm::dmat3 biaxial_orientation(glm::dvec3 x_axis, glm::dvec3 z_axis) {
  const glm::dvec3 z = checked_unit(z_axis, "z_axis");
  checked_unit(x_axis, "x_axis");
  const glm::dvec3 xp = x_axis - glm::dot(x_axis, z) * z;
  const double len = glm::length(xp);
  if (!(len > 1e-9 * glm::length(x_axis)))
    throw std::invalid_argument("x_axis must not be parallel to z_axis");
  const glm::dvec3 x = xp / len;
  return glm::dmat3(x, glm::cross(z, x), z);
}

glm::dmat3 rotate_stage(const glm::dmat3& crystal_to_lab, double stage_rad) {
  return stage_rotation(stage_rad) * crystal_to_lab;
}

double optic_angle_2v_rad(double nalpha, double nbeta, double ngamma) {
  const double a2 = nalpha * nalpha, b2 = nbeta * nbeta, g2 = ngamma * ngamma;
  const double den = b2 * (g2 - a2);
  if (!(den > 0.0)) return 0.0;  // isotropic: no optic angle
  // Born & Wolf §15.3, Nesse 2012 ch. 7: cos²Vz = nα²(nγ² − nβ²) / (nβ²(nγ² − nα²)).
  const double cos2 = std::clamp(a2 * (g2 - b2) / den, 0.0, 1.0);
  return 2.0 * std::acos(std::sqrt(cos2));
}

Crystal crystal_from_indices(const CrystalIndices& c) {
  auto check = [](const char* key, double n) {
    try {
      check_refractive_index(n);
    } catch (const BadValue& b) {
      throw InputError("", key, number_text(n), b.why);
    }
  };
  if (c.uniaxial) {
    check("no", c.no);
    check("ne", c.ne);
  } else {
    check("nalpha", c.nalpha);
    check("nbeta", c.nbeta);
    check("ngamma", c.ngamma);
    try {
      check_biaxial_order(c.nalpha, c.nbeta, c.ngamma);
    } catch (const BadValue& b) {
      throw InputError(
          "", "", number_text(c.nalpha) + ", " + number_text(c.nbeta) + ", " + number_text(c.ngamma), b.why);
    }
  }
  if (c.uniaxial) return Crystal::uniaxial_constant("custom uniaxial", c.no, c.ne);
  return Crystal::biaxial_constant("custom biaxial", c.nalpha, c.nbeta, c.ngamma);
}

}  // namespace pmsim
