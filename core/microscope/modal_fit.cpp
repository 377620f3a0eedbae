#include "core/microscope/modal_fit.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace pmsim {

namespace {
constexpr double x_of(double nm) { return 1.0 / (nm * nm); }
// Lagrange basis in x through the three anchors, and its derivative in x.
void lagrange(double x, double L[3], double dL[3]) {
  const double X[3] = {x_of(ModalFit::kAnchorNm[0]), x_of(ModalFit::kAnchorNm[1]),
                       x_of(ModalFit::kAnchorNm[2])};
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const double den = (X[i] - X[j]) * (X[i] - X[k]);
    L[i] = (x - X[j]) * (x - X[k]) / den;
    dL[i] = ((x - X[j]) + (x - X[k])) / den;
  }
}
}  // namespace

void modes_in_basis(const PlateModes& m, const glm::dvec3& k_air, glm::dvec2& e1, glm::dvec2& e2) {
  glm::dvec3 a, b;
  transverse_basis(k_air, a, b);
  e1 = {glm::dot(m.e1, a), glm::dot(m.e1, b)};
  e2 = {glm::dot(m.e2, a), glm::dot(m.e2, b)};
  const double l1 = glm::length(e1), l2 = glm::length(e2);
  e1 = l1 > 1e-300 ? e1 / l1 : glm::dvec2(1.0, 0.0);
  e2 = l2 > 1e-300 ? e2 / l2 : glm::dvec2(-e1.y, e1.x);
}

void ModalFit::fit(const PreparedPlate anchors[3], const glm::dvec3& k_air) {
  for (int i = 0; i < 3; ++i) {
    const PlateModes m = plate_modes(anchors[i], k_air);
    gamma_[i] = m.retardation_nm;
    modes_in_basis(m, k_air, e1_[i], e2_[i]);
    t1_[i] = m.t1;
    t2_[i] = m.t2;
    // A mode direction is defined up to sign; keep the anchors on one branch so that the
    // interpolation does not pass through zero.
    if (i > 0) {
      if (glm::dot(e1_[i], e1_[0]) < 0) e1_[i] = -e1_[i];
      if (glm::dot(e2_[i], e2_[0]) < 0) e2_[i] = -e2_[i];
    }
  }
}

void ModalFit::assign(const double gamma_nm[3], const glm::dvec2 e1[3], const glm::dvec2 e2[3],
                      const double t1[3], const double t2[3]) {
  for (int i = 0; i < 3; ++i) {
    gamma_[i] = gamma_nm[i];
    e1_[i] = e1[i];
    e2_[i] = e2[i];
    t1_[i] = t1[i];
    t2_[i] = t2[i];
  }
}

ModalPoint ModalFit::at(double wavelength_nm, double s) const {
  double L[3], dL[3];
  lagrange(x_of(wavelength_nm), L, dL);
  ModalPoint p;
  p.gamma_nm = s * (L[0] * gamma_[0] + L[1] * gamma_[1] + L[2] * gamma_[2]);
  // dΓ/dλ = dΓ/dx · dx/dλ, dx/dλ = −2/λ³
  const double dx = -2.0 / (wavelength_nm * wavelength_nm * wavelength_nm);
  p.dgamma_dnm = s * (dL[0] * gamma_[0] + dL[1] * gamma_[1] + dL[2] * gamma_[2]) * dx;
  p.e1 = L[0] * e1_[0] + L[1] * e1_[1] + L[2] * e1_[2];
  p.e2 = L[0] * e2_[0] + L[1] * e2_[1] + L[2] * e2_[2];
  const double l1 = glm::length(p.e1), l2 = glm::length(p.e2);
  p.e1 = l1 > 1e-300 ? p.e1 / l1 : e1_[1];
  p.e2 = l2 > 1e-300 ? p.e2 / l2 : e2_[1];
  p.t1 = std::max(0.0, L[0] * t1_[0] + L[1] * t1_[1] + L[2] * t1_[2]);
  p.t2 = std::max(0.0, L[0] * t2_[0] + L[1] * t2_[1] + L[2] * t2_[2]);
  if (s != 1.0) {
    p.t1 = std::pow(p.t1, s);
    p.t2 = std::pow(p.t2, s);
  }
  return p;
}

double ModalFit::retardation_nm(double wavelength_nm) const {
  double L[3], dL[3];
  lagrange(x_of(wavelength_nm), L, dL);
  return L[0] * gamma_[0] + L[1] * gamma_[1] + L[2] * gamma_[2];
}

}  // namespace pmsim

namespace pmsim {

namespace {
// Coefficients of one anchor from the mode directions and transmissions.
void terms_at(const glm::dvec2& e1in, const glm::dvec2& e2in, double t1, double t2, const TrainState& t,
              const glm::dmat2* lens_in, const glm::dmat2* lens_out, double out[5]) {
  glm::dvec2 e1 = e1in, e2 = e2in;
  double det = e1.x * e2.y - e1.y * e2.x;
  if (std::fabs(det) < 1e-9) {
    e2 = {-e1.y, e1.x};
    det = 1.0;
  }
  const glm::dvec2 d1{e2.y / det, -e2.x / det}, d2{-e1.y / det, e1.x / det};
  // The condenser acts on the polarizer's field before the sample splits it into modes; the
  // objective on each mode's field after it.
  const glm::dvec2 pol = lens_in ? *lens_in * t.polarizer : t.polarizer;
  const double a[2] = {t1 * glm::dot(d1, pol), t2 * glm::dot(d2, pol)};
  const glm::dvec2 f1 = lens_out ? *lens_out * e1 : e1, f2 = lens_out ? *lens_out * e2 : e2;
  for (int i = 0; i < 5; ++i) out[i] = 0.0;
  for (int o = 0; o < t.outputs; ++o) {
    double amp[4];
    int sm[4], sk[4], n = 0;
    for (int m = 0; m < 2; ++m) {
      const glm::dvec2& em = m == 0 ? f1 : f2;
      for (int k = 0; k < t.comp_modes; ++k) {
        const double g = t.comp_modes == 1
                             ? glm::dot(t.output[o], em)
                             : glm::dot(t.output[o], t.comp_dir[k]) * glm::dot(t.comp_dir[k], em);
        amp[n] = g * a[m];
        sm[n] = m;
        sk[n] = k;
        ++n;
      }
    }
    for (int i = 0; i < n; ++i) {
      out[0] += amp[i] * amp[i];
      for (int j = i + 1; j < n; ++j) {
        const int dm = sm[i] - sm[j], dk = sk[i] - sk[j];
        const double v = 2.0 * amp[i] * amp[j];
        if (dk == 0)
          out[1] += v;  // cos φ
        else if (dm == 0)
          out[2] += v;  // cos χ
        else if (dm == dk)
          out[3] += v;  // cos(φ + χ)
        else
          out[4] += v;  // cos(φ − χ)
      }
    }
  }
}
}  // namespace

ModalTerms make_modal_terms(const ModalFit& f, const TrainState& train, double s, const glm::dmat2* lens_in,
                            const glm::dmat2* lens_out) {
  ModalTerms m;
  for (int a = 0; a < 3; ++a) {
    m.gamma_nm[a] = s * f.gamma_[a];
    double c[5];
    const double t1 = s == 1.0 ? f.t1_[a] : std::pow(f.t1_[a], s);
    const double t2 = s == 1.0 ? f.t2_[a] : std::pow(f.t2_[a], s);
    terms_at(f.e1_[a], f.e2_[a], t1, t2, train, lens_in, lens_out, c);
    for (int i = 0; i < 5; ++i) m.c[i][a] = c[i];
  }
  return m;
}

ModalFit identity_modal_fit() {
  const double gamma[3] = {0.0, 0.0, 0.0}, t[3] = {1.0, 1.0, 1.0};
  const glm::dvec2 e1[3] = {{1.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}}, e2[3] = {{0.0, 1.0}, {0.0, 1.0}, {0.0, 1.0}};
  ModalFit f;
  f.assign(gamma, e1, e2, t, t);
  return f;
}

ModalTerms identity_modal_terms(const TrainState& train, const glm::dmat2* lens_in,
                                const glm::dmat2* lens_out) {
  ModalTerms m;
  double c[5];
  terms_at({1.0, 0.0}, {0.0, 1.0}, 1.0, 1.0, train, lens_in, lens_out, c);
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 5; ++i) m.c[i][a] = c[i];
  return m;
}

void modal_anchor_weights(double wavelength_nm, double L[3], double dL_dnm[3]) {
  double dLx[3];
  lagrange(x_of(wavelength_nm), L, dLx);
  const double dx = -2.0 / (wavelength_nm * wavelength_nm * wavelength_nm);
  for (int i = 0; i < 3; ++i) dL_dnm[i] = dLx[i] * dx;
}

}  // namespace pmsim
