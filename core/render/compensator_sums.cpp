#include "core/render/compensator_sums.h"

#include <cmath>

#include <glm/mat2x2.hpp>
#include <tbb/parallel_for.h>

#include "core/microscope/modal_fit.h"
#include "core/microscope/modal_units.h"
#include "core/render/band_integral.h"

namespace pmsim {

namespace {

constexpr int kDirFloats = 27;

// The band average of cos ϑ over band i (W·cos ϑ at one spectral line).
glm::dvec3 band_cosine(const SpectralLevel& L, int i, double theta, double dtheta) {
  if (L.monochromatic) return L.weight[i] * std::cos(theta);
  return oscillating_band(L.weight[i], L.moment[i] * (6.0 / L.band_nm), theta, dtheta, L.band_nm);
}

// One direction's φ, φ+χ and φ−χ sums (gamma_nm: its Γ at the anchors), as modal_general_xyz
// takes φ and its slope per band.
void direction_sums(const double gamma_nm[3], const SpectralLevel& L, float* out) {
  const double two_pi = 6.283185307179586;
  glm::dvec3 s[3][3]{};
  for (int i = 0; i < L.n; ++i) {
    const double* w = L.anchor_w[i].data();
    const double* dw = L.anchor_dw[i].data();
    const double lam = L.nm[i];
    const double g = w[0] * gamma_nm[0] + w[1] * gamma_nm[1] + w[2] * gamma_nm[2];
    const double dg = dw[0] * gamma_nm[0] + dw[1] * gamma_nm[1] + dw[2] * gamma_nm[2];
    const double phi = two_pi * g / lam;                        // φ = 2πΓ/λ
    const double dphi = two_pi * (dg / lam - g / (lam * lam));  // dφ/dλ
    const double chi = L.train[i].chi_rad, dchi = L.train[i].dchi_dnm;
    const glm::dvec3 osc[3] = {band_cosine(L, i, phi, dphi), band_cosine(L, i, phi + chi, dphi + dchi),
                               band_cosine(L, i, phi - chi, dphi - dchi)};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) s[k][a] += w[a] * osc[k];
  }
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) out[9 * k + 3 * a + c] = static_cast<float>(s[k][a][c]);
}

}  // namespace

CompensatorSums compensator_sums(const EvaluationPlan& plan, const SpectralLevel& L, const std::atomic<bool>* cancel) {
  CompensatorSums sums;
  for (int i = 0; i < L.n; ++i) {
    const double* w = L.anchor_w[i].data();
    const double* dw = L.anchor_dw[i].data();
    const glm::dvec3 chi = band_cosine(L, i, L.train[i].chi_rad, L.train[i].dchi_dnm);
    for (int a = 0; a < 3; ++a) {
      sums.steady[a] += L.weight[i] * w[a] + L.moment[i] * dw[a];
      sums.chi[a] += w[a] * chi;
    }
  }
  const int units = static_cast<int>(plan.units().size());
  const int per_unit = plan.dirs_per_unit();
  std::vector<float> dirs(static_cast<std::size_t>(units) * per_unit * kDirFloats, 0.0f);
  tbb::parallel_for(tbb::blocked_range<int>(0, units, 256), [&](const tbb::blocked_range<int>& b) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    for (int u = b.begin(); u != b.end(); ++u) {
      if (plan.needs_exact(u)) continue;
      const EvalUnit& unit = plan.units()[u];
      const double scale = modal_thickness_scale(unit, plan.domains()[unit.domain]);
      for (int d = 0; d < plan.dirs_of(unit); ++d) {
        const std::size_t at = static_cast<std::size_t>(u) * per_unit + d;
        const ModalFit& fit = plan.modal_fits()[at];
        const double gamma[3] = {scale * fit.gamma_at_anchor(0), scale * fit.gamma_at_anchor(1),
                                 scale * fit.gamma_at_anchor(2)};  // make_modal_terms' Γ
        direction_sums(gamma, L, &dirs[at * kDirFloats]);
      }
    }
  });
  if (!(cancel && cancel->load())) sums.dirs = std::move(dirs);
  return sums;
}

glm::dvec3 evaluate_unit_from_sums(const EvaluationPlan& plan, const SpectralLevel& L, const TrainState& train,
                                   const CompensatorSums& sums, int u) {
  if (plan.needs_exact(u)) return evaluate_unit(plan, L, u);
  const EvalUnit& unit = plan.units()[u];
  const double scale = modal_thickness_scale(unit, plan.domains()[unit.domain]);
  const int D = plan.dirs_of(unit);
  glm::dvec3 xyz(0.0);
  for (int d = 0; d < D; ++d) {
    const std::size_t at = static_cast<std::size_t>(u) * plan.dirs_per_unit() + d;
    glm::dmat2 jc, jo;
    plan.lens_jones(plan.dir(unit, d), jc, jo);
    const ModalTerms m = make_modal_terms(plan.modal_fits()[at], train, scale, &jc, &jo);
    const float* s = &sums.dirs[at * kDirFloats];
    for (int a = 0; a < 3; ++a) {
      xyz += sums.steady[a] * m.c[0][a] + sums.chi[a] * m.c[2][a];
      for (int k = 0; k < 3; ++k) {
        const float* v = s + 9 * k + 3 * a;
        xyz += glm::dvec3(v[0], v[1], v[2]) * m.c[k == 0 ? 1 : k + 2][a];
      }
    }
  }
  xyz /= D;
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(xyz[k])) xyz[k] = 0.0;
  return xyz;
}

}  // namespace pmsim
