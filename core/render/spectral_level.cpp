#include "core/render/spectral_level.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <tbb/parallel_for.h>

#include "core/render/band_integral.h"
#include "core/render/fast_trig.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/spectral_bands.h"

namespace pmsim {

SpectralLevel make_spectral_level(const EvaluationPlan& plan, int n) {
  SpectralLevel L;
  const double mono = plan.scene().render.single_wavelength_nm;
  if (mono > 0) {
    L.n = 1;
    L.monochromatic = true;
    L.nm = {mono};
    L.weight = {glm::dvec3(1.0)};
    L.moment = {glm::dvec3(0.0)};
  } else {
    L.n = std::max(1, n);
    const SpectralBands bands = spectral_bands(L.n, plan.scene().illuminant);
    L.band_nm = bands.width_nm[0];
    for (int i = 0; i < L.n; ++i) L.nm.push_back(bands.centre_nm(i));
    L.weight = bands.weight;
    L.moment = bands.moment;
  }
  for (double nm : L.nm) {
    L.train.push_back(make_train(plan.scene(), plan.compensator(), nm));
    std::array<double, 3> w, dw;
    modal_anchor_weights(nm, w.data(), dw.data());
    L.anchor_w.push_back(w);
    L.anchor_dw.push_back(dw);
  }
  const int padded = (L.n + 3) / 4 * 4;  // the modal kernel takes two or four bands at a time
  for (int a = 0; a < 3; ++a) {
    L.aw[a].assign(padded, 0.0);  // zero weights: the padding band contributes nothing
    L.adw[a].assign(padded, 0.0);
  }
  L.inv_nm.assign(padded, 1.0 / L.nm.back());
  for (int i = 0; i < L.n; ++i) {
    L.inv_nm[i] = 1.0 / L.nm[i];
    L.moment6h.push_back(L.band_nm > 0 ? L.moment[i] * (6.0 / L.band_nm) : glm::dvec3(0.0));
    for (int a = 0; a < 3; ++a) {
      L.aw[a][i] = L.anchor_w[i][a];
      L.adw[a][i] = L.anchor_dw[i][a];
      L.steady[a] += L.weight[i] * L.anchor_w[i][a] + L.moment[i] * L.anchor_dw[i][a];
    }
  }
  if (plan.any_exact()) {
    // Every domain an exact unit shows, at every band, in parallel over domains (each plate
    // independent, the same values in any order).
    const std::size_t nd = plan.domains().size();
    L.prepared_slot.assign(nd, -1);
    std::vector<int> todo;
    for (std::size_t u = 0; u < plan.units().size(); ++u) {
      const int d = plan.units()[u].domain;
      if (plan.needs_exact(static_cast<int>(u)) && L.prepared_slot[d] < 0 && plan.domains()[d].crystal) {
        L.prepared_slot[d] = static_cast<int>(todo.size());
        todo.push_back(d);
      }
    }
    L.prepared.assign(L.n, std::vector<PreparedPlate>(todo.size()));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 4), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t j = r.begin(); j != r.end(); ++j)
        for (int i = 0; i < L.n; ++i) L.prepared[i][j] = plan.prepare(todo[j], L.nm[i]);
    });
  }
  return L;
}

SpectralLevel level_in_train(const SpectralLevel& level, const Scene& scene, const CompensatorPlate& compensator) {
  SpectralLevel L = level;
  for (int i = 0; i < L.n; ++i) L.train[i] = make_train(scene, compensator, L.nm[i]);
  return L;
}

double unit_transmission(const EvaluationPlan& plan, const SpectralLevel& L, int u, int i) {
  const EvalUnit& unit = plan.units()[u];
  const OpticalDomain& dom = plan.domains()[unit.domain];
  const TrainState& train = L.train[i];
  const int D = plan.dirs_of(unit);
  double t = 0.0;
  if (!dom.crystal || unit.thickness_um <= 0.0) {
    for (int d = 0; d < D; ++d)
      t += jones_transmission(train, plan.with_lenses(JonesMatrix::identity(), plan.dir(unit, d)));
    return t / D;
  }
  const PreparedPlate* ready = L.plate(i, unit.domain);
  PreparedPlate p = ready ? *ready : plan.prepare(unit.domain, L.nm[i]);
  p.thickness_um = unit.thickness_um;
  for (int d = 0; d < D; ++d)
    t += jones_transmission(train, plan.with_lenses(plate_jones(p, plan.dir(unit, d)), plan.dir(unit, d)));
  t /= D;
  return std::isfinite(t) ? std::max(0.0, t) : 0.0;
}

namespace {

// Two bands at a time in SSE2 registers (GCC/Clang vector extensions: the x86-64 baseline, no
// target flags needed), or four in AVX2 registers where the CPU has them; selects are masks, so
// nothing branches. Both widths do the same IEEE operations per lane (AVX2 without FMA: nothing
// is contracted), so they give the same bits.
typedef double v2d __attribute__((vector_size(16)));
typedef long long v2l __attribute__((vector_size(16)));
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4l __attribute__((vector_size(32)));
template <class V>
struct Mask;
template <>
struct Mask<v2d> {
  using type = v2l;
};
template <>
struct Mask<v4d> {
  using type = v4l;
};

#define PMSIM_LANE [[gnu::always_inline]] inline  // inlined into the AVX2 kernel, compiled there
// The helpers pass 256-bit vectors by value, which GCC warns changes the ABI without AVX; they are
// always inlined, so no call with that ABI exists. (GCC reports it at the end of the file, so the
// warning is off for the rest of it.)
#pragma GCC diagnostic ignored "-Wpsabi"

template <class V>
PMSIM_LANE V load(const double* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class V>
PMSIM_LANE V splat(double x) {
  V v;
  for (std::size_t i = 0; i < sizeof(V) / sizeof(double); ++i) v[i] = x;
  return v;
}
template <class V, class M = typename Mask<V>::type>
PMSIM_LANE V select(M mask, V a, V b) {
  M ai, bi;
  std::memcpy(&ai, &a, sizeof a);
  std::memcpy(&bi, &b, sizeof b);
  const M r = (ai & mask) | (bi & ~mask);
  V out;
  std::memcpy(&out, &r, sizeof out);
  return out;
}
template <class V>
PMSIM_LANE V vabs(V x) {
  return select(x < splat<V>(0.0), -x, x);
}

// sin and cos of the lanes (fast_trig.h's algorithm without branches): nearest quadrant by the
// 1.5·2⁵² rounding trick (exact for |x| < 2⁵¹ in round-to-nearest), Cody–Waite reduction,
// Taylor polynomials on |r| ≤ π/4 (truncation < 4e-13), the quadrant k mod 4 selecting and signing
// them.
template <class V>
PMSIM_LANE void sincos_lanes(V x, V& s, V& c) {
  const V magic = splat<V>(6755399441055744.0);  // 1.5·2⁵²
  const V k = (x * splat<V>(kTwoOverPi) + magic) - magic;
  const V r = (x - k * splat<V>(kPio2Hi)) - k * splat<V>(kPio2Lo);
  V sr, cr;
  sincos_taylor(r, sr, cr);
  const V k4 = (k * 0.25 + magic) - magic;
  const V q0 = k - 4.0 * k4;                                   // −2 … 2, ≡ k mod 4
  const V q = select(q0 < splat<V>(0.0), q0 + 4.0, q0);        // 0 … 3
  const auto odd = vabs(q - 2.0) == splat<V>(1.0);
  const V ps = select(odd, cr, sr), pc = select(odd, sr, cr);
  s = select(q >= splat<V>(2.0), -ps, ps);             // sin < 0 in quadrants 2, 3
  c = select(vabs(q - 1.5) < splat<V>(1.0), -pc, pc);  // cos < 0 in quadrants 1, 2
}

// The band loop of modal_plain_xyz, sizeof(V)/8 bands at a time: the two scalars per band.
template <class V>
PMSIM_LANE void modal_plain_bands(const ModalTerms& m, const SpectralLevel& L, double* va, double* vb) {
  constexpr int kLanes = sizeof(V) / sizeof(double);
  const double two_pi = 6.283185307179586;
  const V half_h = splat<V>(0.5 * L.band_nm);
  const V g0 = splat<V>(m.gamma_nm[0]), g1 = splat<V>(m.gamma_nm[1]), g2 = splat<V>(m.gamma_nm[2]);
  const V k0 = splat<V>(m.c[1][0]), k1 = splat<V>(m.c[1][1]), k2 = splat<V>(m.c[1][2]);
  const int n = L.n;
  for (int i = 0; i < n; i += kLanes) {  // the level's arrays are padded to a multiple of 4
    const V w0 = load<V>(&L.aw[0][i]), w1 = load<V>(&L.aw[1][i]), w2 = load<V>(&L.aw[2][i]);
    const V il = load<V>(&L.inv_nm[i]);
    const V g = w0 * g0 + w1 * g1 + w2 * g2;
    const V dg = load<V>(&L.adw[0][i]) * g0 + load<V>(&L.adw[1][i]) * g1 + load<V>(&L.adw[2][i]) * g2;
    const V phi = two_pi * g * il;               // φ = 2πΓ/λ
    const V dphi = two_pi * il * (dg - g * il);  // dφ/dλ
    const V c1 = w0 * k0 + w1 * k1 + w2 * k2;
    const V x = dphi * half_h;
    V s0, c0, sx, cx;
    sincos_lanes(phi, s0, c0);
    sincos_lanes(x, sx, cx);
    const V x2 = x * x;
    const auto small = vabs(x) < splat<V>(1e-3);  // series there: sinc = 1 − x²/6, q = x/3 − x³/30
    const V inv = 1.0 / select(small, splat<V>(1.0), x);
    const V sinc = select(small, 1.0 - x2 * (1.0 / 6.0), sx * inv);
    const V q = select(small, x * (1.0 / 3.0 - x2 * (1.0 / 30.0)), (sx - x * cx) * inv * inv);
    const V a = c1 * c0 * sinc, b = c1 * s0 * q;
    std::memcpy(va + i, &a, sizeof a);
    std::memcpy(vb + i, &b, sizeof b);
  }
}

[[gnu::target("avx2")]] void modal_plain_bands_avx2(const ModalTerms& m, const SpectralLevel& L, double* va,
                                                    double* vb) {
  modal_plain_bands<v4d>(m, L, va, vb);
}

const bool kHaveAvx2 = __builtin_cpu_supports("avx2");

// The common case (no compensator, bands): T(λ) = C0(λ) + Cφ(λ)·cos φ(λ) band-averaged (see
// band_integral.h); the C0 part is linear in the anchors and precomputed per level. The band loop
// writes two scalars per band; the XYZ sum follows.
glm::dvec3 modal_plain_xyz(const ModalTerms& m, const SpectralLevel& L, double* va, double* vb) {
  if (kHaveAvx2)
    modal_plain_bands_avx2(m, L, va, vb);
  else
    modal_plain_bands<v2d>(m, L, va, vb);
  const int n = L.n;
  glm::dvec3 xyz = L.steady[0] * m.c[0][0] + L.steady[1] * m.c[0][1] + L.steady[2] * m.c[0][2];
  for (int i = 0; i < n; ++i) xyz += L.weight[i] * va[i] - L.moment6h[i] * vb[i];
  return xyz;
}

constexpr int kChunk = 256;  // the plain path's band arrays on the stack

// The general band loop of one direction's terms (a compensator's χ terms, one spectral line, or
// more bands than the plain path holds), added to `xyz` band by band.
void modal_general_xyz(const ModalTerms& m, const SpectralLevel& L, bool comp, glm::dvec3& xyz) {
  const double two_pi = 6.283185307179586;
  const double h = L.band_nm;
  for (int i = 0; i < L.n; ++i) {
    const double* w = L.anchor_w[i].data();
    const double* dw = L.anchor_dw[i].data();
    const double lam = L.nm[i];
    const double g = w[0] * m.gamma_nm[0] + w[1] * m.gamma_nm[1] + w[2] * m.gamma_nm[2];
    const double dg = dw[0] * m.gamma_nm[0] + dw[1] * m.gamma_nm[1] + dw[2] * m.gamma_nm[2];
    const double phi = two_pi * g / lam;                        // φ = 2πΓ/λ
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

// A unit's XYZ from its directions' terms (`terms(d)`): the plain path's vector band loop where
// it holds, else the general loop; the mean over the directions, non-finite sums zeroed.
template <class Terms>
glm::dvec3 modal_xyz(const EvaluationPlan& plan, const SpectralLevel& L, int u, bool comp, const Terms& terms) {
  const EvalUnit& unit = plan.units()[u];
  const int D = plan.dirs_of(unit);
  glm::dvec3 xyz(0.0);
  if (!comp && !L.monochromatic && L.n <= kChunk) {
    alignas(32) double va[kChunk + 3], vb[kChunk + 3];
    for (int d = 0; d < D; ++d) xyz += modal_plain_xyz(terms(d), L, va, vb);
  } else {
    for (int d = 0; d < D; ++d) modal_general_xyz(terms(d), L, comp, xyz);
  }
  xyz /= D;
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(xyz[k])) xyz[k] = 0.0;
  return xyz;
}

glm::dvec3 modal_unit_xyz(const EvaluationPlan& plan, const SpectralLevel& L, int u) {
  const std::size_t first = static_cast<std::size_t>(u) * plan.dirs_per_unit();
  return modal_xyz(plan, L, u, plan.compensator().present,
                   [&](int d) -> const ModalTerms& { return plan.modal_terms()[first + d]; });
}

}  // namespace

bool shares_band_loop(const EvaluationPlan& plan, const SpectralLevel& L, int u) {
  return !plan.needs_exact(u) && !plan.compensator().present && !L.monochromatic && L.n <= kChunk;
}

void evaluate_unit_in_trains(const EvaluationPlan& plan, const SpectralLevel& L, int u,
                             const std::vector<TrainState>& trains, glm::dvec3* xyz) {
  alignas(32) double va[kChunk + 3], vb[kChunk + 3];
  const EvalUnit& unit = plan.units()[u];
  const double scale = modal_thickness_scale(unit, plan.domains()[unit.domain]);
  const int D = plan.dirs_of(unit);
  const std::size_t T = trains.size();
  for (std::size_t t = 0; t < T; ++t) xyz[t] = glm::dvec3(0.0);
  for (int d = 0; d < D; ++d) {
    const ModalFit& fit = plan.modal_fits()[static_cast<std::size_t>(u) * plan.dirs_per_unit() + d];
    glm::dmat2 jc, jo;
    plan.lens_jones(plan.dir(unit, d), jc, jo);
    ModalTerms first = make_modal_terms(fit, trains[0], scale, &jc, &jo);
    // Cφ ≡ 1 at every anchor: the Lagrange weights sum to 1, so the bands give cos φ·sinc and sin φ·q.
    ModalTerms unit_phase = first;
    for (int a = 0; a < 3; ++a) unit_phase.c[1][a] = 1.0;
    if (kHaveAvx2)
      modal_plain_bands_avx2(unit_phase, L, va, vb);
    else
      modal_plain_bands<v2d>(unit_phase, L, va, vb);
    glm::dvec3 sum[3]{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
    for (int i = 0; i < L.n; ++i) {
      const glm::dvec3 band = L.weight[i] * va[i] - L.moment6h[i] * vb[i];
      for (int a = 0; a < 3; ++a) sum[a] += L.aw[a][i] * band;
    }
    for (std::size_t t = 0; t < T; ++t) {
      const ModalTerms m = t == 0 ? first : make_modal_terms(fit, trains[t], scale, &jc, &jo);
      for (int a = 0; a < 3; ++a) xyz[t] += L.steady[a] * m.c[0][a] + sum[a] * m.c[1][a];
    }
  }
  for (std::size_t t = 0; t < T; ++t) {
    xyz[t] /= D;
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(xyz[t][k])) xyz[t][k] = 0.0;
  }
}

glm::dvec3 evaluate_unit_in_train(const EvaluationPlan& plan, const SpectralLevel& L, const TrainState& train,
                                  int u) {
  if (plan.needs_exact(u)) return evaluate_unit(plan, L, u);
  const EvalUnit& unit = plan.units()[u];
  const double scale = modal_thickness_scale(unit, plan.domains()[unit.domain]);
  const std::size_t first = static_cast<std::size_t>(u) * plan.dirs_per_unit();
  return modal_xyz(plan, L, u, train.comp_modes == 2, [&](int d) {
    glm::dmat2 jc, jo;
    plan.lens_jones(plan.dir(unit, d), jc, jo);
    return make_modal_terms(plan.modal_fits()[first + d], train, scale, &jc, &jo);
  });
}

glm::dvec3 evaluate_unit(const EvaluationPlan& plan, const SpectralLevel& L, int u) {
  if (!plan.needs_exact(u)) return modal_unit_xyz(plan, L, u);
  glm::dvec3 xyz(0.0);
  for (int i = 0; i < L.n; ++i) xyz += L.weight[i] * unit_transmission(plan, L, u, i);
  return xyz;
}

}  // namespace pmsim
