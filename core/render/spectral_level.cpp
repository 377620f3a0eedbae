#include "core/render/spectral_level.h"

#include <algorithm>
#include <cmath>

#include "core/render/band_integral.h"
#include "core/spectrum/cie.h"

namespace pmsim {

SpectralLevel make_spectral_level(const MicroscopeSetup& S, int n) {
  SpectralLevel L;
  const double mono = S.scene.render.single_wavelength_nm;
  if (mono > 0) {
    L.n = 1;
    L.monochromatic = true;
    L.nm = {mono};
    L.weight = {glm::dvec3(1.0)};
    L.moment = {glm::dvec3(0.0)};
  } else {
    L.n = std::max(1, n);
    L.band_nm = (kVisibleMaxNm - kVisibleMinNm) / L.n;
    for (int i = 0; i < L.n; ++i) {
      const double lo = kVisibleMinNm + i * L.band_nm;
      L.nm.push_back(lo + 0.5 * L.band_nm);
      // Midpoint sub-rule at ≤ 1 nm: the observer tables are 1–5 nm data, linear in between.
      const int sub = std::max(1, static_cast<int>(std::ceil(L.band_nm)));
      glm::dvec3 w(0.0), m(0.0);
      for (int s = 0; s < sub; ++s) {
        const double t = (s + 0.5) * L.band_nm / sub;
        const glm::dvec3 ws = observer_weight(S.scene.illuminant, lo + t) * (L.band_nm / sub);
        w += ws;
        m += ws * (t - 0.5 * L.band_nm);
      }
      L.weight.push_back(w);
      L.moment.push_back(m);
    }
    // Normalise so that T ≡ 1 gives the illuminant white exactly at every n (the sub-rule above
    // differs from the tables' own quadrature by ~1e-6).
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& w : L.weight) sum += w;
    const glm::dvec3 scale = illuminant_white_xyz(S.scene.illuminant) / sum;
    for (int i = 0; i < L.n; ++i) {
      L.weight[i] *= scale;
      L.moment[i] *= scale;
    }
  }
  for (double nm : L.nm) {
    L.train.push_back(make_train(S.scene, S.compensator, nm));
    std::array<double, 3> w, dw;
    modal_anchor_weights(nm, w.data(), dw.data());
    L.anchor_w.push_back(w);
    L.anchor_dw.push_back(dw);
  }
  const bool any_exact = S.plate_model == PlateModel::Exact ||
                         std::find(S.unit_exact.begin(), S.unit_exact.end(), 1) != S.unit_exact.end();
  if (any_exact) {
    L.prepared.resize(L.n);
    for (int i = 0; i < L.n; ++i)
      for (std::size_t d = 0; d < S.domains.size(); ++d)
        L.prepared[i].push_back(S.domains[d].crystal ? S.prepare(static_cast<int>(d), L.nm[i])
                                                     : PreparedPlate{});
  }
  return L;
}

double unit_transmission(const MicroscopeSetup& S, const SpectralLevel& L, int u, int i) {
  const EvalUnit& unit = S.units[u];
  const OpticalDomain& dom = S.domains[unit.domain];
  const TrainState& train = L.train[i];
  const int D = S.dirs_of(unit);
  double t = 0.0;
  if (!dom.crystal || unit.thickness_um <= 0.0) {
    for (int d = 0; d < D; ++d)
      t += jones_transmission(train, S.with_lenses(JonesMatrix::identity(), S.dir(unit, d)));
    return t / D;
  }
  PreparedPlate p = L.prepared.empty() ? S.prepare(unit.domain, L.nm[i]) : L.prepared[i][unit.domain];
  p.thickness_um = unit.thickness_um;
  for (int d = 0; d < D; ++d)
    t += jones_transmission(train, S.with_lenses(plate_jones(p, S.dir(unit, d)), S.dir(unit, d)));
  t /= D;
  return std::isfinite(t) ? std::max(0.0, t) : 0.0;
}

namespace {

glm::dvec3 modal_unit_xyz(const MicroscopeSetup& S, const SpectralLevel& L, int u) {
  const EvalUnit& unit = S.units[u];
  const int D = S.dirs_of(unit);
  const bool comp = S.compensator.present;
  const double two_pi = 6.283185307179586;
  const double h = L.band_nm;
  glm::dvec3 xyz(0.0);
  for (int d = 0; d < D; ++d) {
    const ModalTerms& m = S.terms[static_cast<std::size_t>(u) * S.dirs_per_unit + d];
    for (int i = 0; i < L.n; ++i) {
      const double* w = L.anchor_w[i].data();
      const double* dw = L.anchor_dw[i].data();
      const double lam = L.nm[i];
      const double g = w[0] * m.gamma_nm[0] + w[1] * m.gamma_nm[1] + w[2] * m.gamma_nm[2];
      const double dg = dw[0] * m.gamma_nm[0] + dw[1] * m.gamma_nm[1] + dw[2] * m.gamma_nm[2];
      const double phi = two_pi * g / lam;                      // φ = 2πΓ/λ
      const double dphi = two_pi * (dg / lam - g / (lam * lam));  // dφ/dλ
      double c[5];
      for (int k = 0; k < 5; ++k) c[k] = w[0] * m.c[k][0] + w[1] * m.c[k][1] + w[2] * m.c[k][2];
      const double dc0 = dw[0] * m.c[0][0] + dw[1] * m.c[0][1] + dw[2] * m.c[0][2];
      const glm::dvec3& W = L.weight[i];
      const glm::dvec3& M = L.moment[i];
      xyz += W * c[0] + M * dc0;
      if (L.monochromatic) {
        xyz += W * (c[1] * std::cos(phi));
        if (comp) {
          const double chi = L.train[i].chi_rad;
          xyz += W * (c[2] * std::cos(chi) + c[3] * std::cos(phi + chi) + c[4] * std::cos(phi - chi));
        }
        continue;
      }
      const glm::dvec3 M6h = M * (6.0 / h);
      if (c[1] != 0.0) xyz += c[1] * oscillating_band(W, M6h, phi, dphi, h);
      if (comp) {
        const double chi = L.train[i].chi_rad, dchi = L.train[i].dchi_dnm;
        if (c[2] != 0.0) xyz += c[2] * oscillating_band(W, M6h, chi, dchi, h);
        if (c[3] != 0.0) xyz += c[3] * oscillating_band(W, M6h, phi + chi, dphi + dchi, h);
        if (c[4] != 0.0) xyz += c[4] * oscillating_band(W, M6h, phi - chi, dphi - dchi, h);
      }
    }
  }
  xyz /= D;
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(xyz[k])) xyz[k] = 0.0;
  return xyz;
}

}  // namespace

glm::dvec3 evaluate_unit(const MicroscopeSetup& S, const SpectralLevel& L, int u) {
  if (!S.needs_exact(u)) return modal_unit_xyz(S, L, u);
  glm::dvec3 xyz(0.0);
  for (int i = 0; i < L.n; ++i) xyz += L.weight[i] * unit_transmission(S, L, u, i);
  return xyz;
}

}  // namespace pmsim
