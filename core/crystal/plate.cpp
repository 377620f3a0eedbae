// Plane-wave eigenmodes of an anisotropic plate and its Jones matrix.
//
// Model and approximations (after Debelov & Kozlov 2013, Born & Wolf §15.2–15.3, Yariv & Yeh
// "Optical Waves in Crystals" ch. 4–5):
// * The incident wave has tangential wave vector q = k0·(k_air.x, k_air.y), conserved through the
//   mounting medium, the plate and back. Inside the crystal each eigenmode has wave normal
//   s_i = (q, k_zi)/n_i with n_i its index for that normal: the Fresnel equation of wave normals
//   is solved as the 2×2 eigenproblem of the impermeability tensor η = ε⁻¹ projected on the
//   plane ⟂ s (eigenvalues 1/n², eigenvectors the D directions). Uniaxial: k_z in closed form
//   (ordinary k_z = ±√(no² − q²); extraordinary from the quadratic kᵀAk = 1 with
//   A = I/ne² + (1/no² − 1/ne²)ccᵀ). Biaxial: the fixed point n ← n(s(n)) for each mode, which
//   contracts by about (nγ − nα)·tanθ/n per step and is iterated to 1e-15.
// * Faces: exact single-interface amplitudes from continuity of tangential E and H (the
//   boundary-value problem of Yariv & Yeh ch. 4; Born & Wolf §1.5 for the isotropic case): at entry the
//   unknowns are the two forward modes and the reflected s and p waves; at exit the transmitted s and p waves
//   and the two backward modes. Each is a 4×4 real linear system. Multiple reflections inside the plate are
//   neglected (their power is ~R² ≈ 1e-6 of the direct wave); so |J|² ≤ 1 without absorption. With fresnel =
//   false the incident field is decomposed on the orthogonal basis nearest to the mode D directions (TE/TM
//   coordinates) and recomposed from it, lossless.
// * TE/TM coordinates: s = unit(ẑ × k), p = s × k; the same (p, s) components describe the field
//   outside relative to k_air, so the Jones matrix is returned in transverse_basis(k_air) after a
//   rotation from (p, s).
// * Absorption (pleochroism): a mode vibrating along D loses intensity at μ = Dᵀ·M·D with
//   M = Σ μ_k·axis_k·axis_kᵀ (the principal absorptions weighted by (D·axis_k)²), over the path
//   d/cos θ_i; the lossless mode shapes are kept (weak absorption).
// * Optical activity: the plate acts on the two modes as exp(−iH), H = (δ/2)σ3 + α σ2 + absorption,
//   Jones' N-matrix combination of linear retardance δ = k0·d·(k_z2 − k_z1) and a rotation
//   α = −ρ·(s·c)²·d/cos θ (gyration along the wave normal ∝ cos² of its angle to the optic axis;
//   the transverse gyration component g11 is neglected). Along the axis this is a pure rotation
//   by ρd; far from it the linear birefringence dominates and the modes are linear again.
// * Walk-off: the lateral ray displacement is reported in PlateModes but not applied: across a
//   30 µm section it is at most a few µm, below a pixel of a thin-section image.
#include "core/crystal/plate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/base/units.h"
#include "core/optics/beer_lambert.h"

namespace pmsim {

void transverse_basis(const glm::dvec3& k, glm::dvec3& a, glm::dvec3& b) {
  glm::dvec3 v = glm::dvec3(1, 0, 0) - k.x * k;
  double len = glm::length(v);
  if (len < 1e-9) {  // k (nearly) along x: only possible at grazing incidence
    v = glm::dvec3(0, 1, 0) - k.y * k;
    len = glm::length(v);
  }
  a = v / len;
  b = glm::cross(k, a);
}

PreparedPlate prepare_plate(const PlateSpec& plate, double wavelength_nm) {
  if (plate.crystal == nullptr) throw std::invalid_argument("PlateSpec.crystal is null");
  const Crystal& c = *plate.crystal;
  PreparedPlate p;
  const glm::dvec3 n = c.principal_indices(wavelength_nm);
  const glm::dmat3& R = plate.crystal_to_lab;
  const glm::dmat3 inv_eps(glm::dvec3(1.0 / (n.x * n.x), 0, 0), glm::dvec3(0, 1.0 / (n.y * n.y), 0),
                           glm::dvec3(0, 0, 1.0 / (n.z * n.z)));
  p.eta = R * inv_eps * glm::transpose(R);  // η_lab = R·diag(1/n²)·Rᵀ
  p.absorbing = c.absorbing();
  if (p.absorbing) {
    const glm::dvec3 mu = c.principal_absorption_per_um(wavelength_nm);
    const glm::dmat3 m(glm::dvec3(mu.x, 0, 0), glm::dvec3(0, mu.y, 0), glm::dvec3(0, 0, mu.z));
    p.mu_tensor = R * m * glm::transpose(R);
  }
  p.optic_axis = R[2];
  p.n_principal = n;
  p.k0_per_um = 2.0 * kPi / (wavelength_nm * 1e-3);
  p.thickness_um = plate.thickness_um;
  p.n_outside = plate.n_outside;
  p.rho_rad_per_um = c.rotatory_power_rad_per_um(wavelength_nm);
  p.mean_n = n.y;
  p.symmetry = c.symmetry();
  p.fresnel = plate.fresnel;
  return p;
}

namespace {

struct Eigen2 {
  double lam_fast, lam_slow;  // eigenvalues 1/n² (fast = larger)
  double fx, fy;              // fast D direction in (p, s) of the wave normal; slow is (−fy, fx)
};

// Symmetric 2×2 [[a, b], [b, c]] in closed form; at degeneracy any orthogonal pair (here p, s).
inline Eigen2 eigen_sym2(double a, double b, double c) {
  const double m = 0.5 * (a + c), h = 0.5 * (a - c);
  const double r = std::sqrt(h * h + b * b);
  Eigen2 e{m + r, m - r, 1.0, 0.0};
  if (r > 0.0) {
    double x, y;
    if (h >= 0.0) {
      x = h + r;
      y = b;
    } else {
      x = b;
      y = r - h;
    }
    const double len = std::sqrt(x * x + y * y);
    e.fx = x / len;
    e.fy = y / len;
  }
  return e;
}

// η projected on the plane ⟂ s, in the basis (p = s_hat × s, s_hat).
inline Eigen2 wave_normal_modes(const glm::dmat3& eta, const glm::dvec3& s, const glm::dvec3& s_hat) {
  const glm::dvec3 p = glm::cross(s_hat, s);
  const glm::dvec3 eta_p = eta * p, eta_s = eta * s_hat;
  return eigen_sym2(glm::dot(p, eta_p), glm::dot(p, eta_s), glm::dot(s_hat, eta_s));
}

inline glm::dvec3 unit(const glm::dvec3& v) { return v / std::sqrt(glm::dot(v, v)); }
inline double kz_for(double n, double q2) { return std::sqrt(std::max(n * n - q2, 0.0)); }

// The root of h(n) = g(n, i) − n on [lo, hi] with h(lo) ≥ 0 ≥ h(hi): Illinois regula falsi,
// bisecting whenever an Illinois step gains less than half the bracket.
template <class G>
double bracketed_mode_index(const G& g, int i, double lo, double hi) {
  double flo = g(lo, i) - lo, fhi = g(hi, i) - hi;
  if (flo <= 0.0) return lo;
  if (fhi >= 0.0) return hi;
  int side = 0;
  for (int it = 0; it < 200 && hi - lo > 4e-16 * hi; ++it) {
    const double width = hi - lo;
    double m = (lo * fhi - hi * flo) / (fhi - flo);
    if (!(m > lo && m < hi)) m = 0.5 * (lo + hi);
    const double fm = g(m, i) - m;
    if (fm == 0.0) return m;
    if (fm > 0.0) {
      lo = m;
      flo = fm;
      if (side == 1) fhi *= 0.5;
      side = 1;
    } else {
      hi = m;
      fhi = fm;
      if (side == -1) flo *= 0.5;
      side = -1;
    }
    if (hi - lo > 0.5 * width) {  // slow progress: bisect once
      const double b = 0.5 * (lo + hi), fb = g(b, i) - b;
      if (fb == 0.0) return b;
      (fb > 0.0 ? lo : hi) = b;
      (fb > 0.0 ? flo : fhi) = fb;
      side = 0;
    }
  }
  return 0.5 * (lo + hi);
}

// The two eigenmodes travelling forward (dir = +1) or backward (dir = −1) for tangential q.
struct ModePair {
  double kz[2];  // units of k0; [0] fast, [1] slow
  double n[2];
  glm::dvec3 s[2];      // wave normals
  double dp[2], ds[2];  // D in TE/TM coordinates of its own wave normal (unit)
  glm::dvec3 D[2];      // unit D vectors
};

ModePair find_modes(const PreparedPlate& P, double qx, double qy, double q2, const glm::dvec3& s_hat,
                    double dir) {
  ModePair mp;
  if (P.symmetry == CrystalSymmetry::Uniaxial) {
    const double no = P.n_principal.x, ne = P.n_principal.z;
    const glm::dvec3& c = P.optic_axis;
    const double kzo = dir * kz_for(no, q2);
    // kᵀAk = 1, A = I/ne² + (1/no² − 1/ne²)ccᵀ (extraordinary wave normals, Born & Wolf §15.3.3):
    // a·k_z² + b·k_z + c0 = 0 with c0 < 0, so one root of each sign; written without cancellation.
    const double g = 1.0 / (no * no) - 1.0 / (ne * ne), ie2 = 1.0 / (ne * ne);
    const double cq = c.x * qx + c.y * qy;
    const double a = ie2 + g * c.z * c.z, b = 2.0 * g * c.z * cq;
    const double c0 = ie2 * q2 + g * cq * cq - 1.0;
    const double disc = std::sqrt(std::max(b * b - 4.0 * a * c0, 0.0));
    const double big = b >= 0.0 ? (-b - disc) / (2.0 * a) : (-b + disc) / (2.0 * a);
    const double other = c0 / (a * big);
    const double kze = (dir > 0) == (big > 0) ? big : other;
    const double n_e = std::sqrt(q2 + kze * kze);
    const bool o_fast = no <= n_e;
    mp.kz[0] = o_fast ? kzo : kze;
    mp.kz[1] = o_fast ? kze : kzo;
  } else {
    // Fixed point n = g(n), g(n) = index of the mode for the wave normal refracted with index n,
    // solved by the secant method on g(n) − n from the indices at the nβ normal; the plain
    // iteration contracts by ~(nγ − nα)·tanθ/n, so a handful of steps reach 1e-15.
    auto g = [&](double n, int i) {
      const glm::dvec3 sv = unit(glm::dvec3(qx, qy, dir * kz_for(n, q2)));
      const Eigen2 e = wave_normal_modes(P.eta, sv, s_hat);
      return 1.0 / std::sqrt(i == 0 ? e.lam_fast : e.lam_slow);
    };
    const Eigen2 e0 = wave_normal_modes(P.eta, unit(glm::dvec3(qx, qy, dir * kz_for(P.mean_n, q2))), s_hat);
    const double start[2] = {1.0 / std::sqrt(e0.lam_fast), 1.0 / std::sqrt(e0.lam_slow)};
    const double n_max = std::max({P.n_principal.x, P.n_principal.y, P.n_principal.z});
    for (int i = 0; i < 2; ++i) {
      double n0 = start[i], f0 = g(n0, i) - n0;
      double n1 = n0 + f0, f1 = f0;
      bool converged = f0 == 0.0;
      if (converged) n1 = n0;
      for (int it = 0; it < 30 && !converged; ++it) {
        f1 = g(n1, i) - n1;
        if (std::abs(f1) <= 1e-15) {
          converged = true;
          break;
        }
        const double den = f1 - f0;
        double n2 = den != 0.0 ? n1 - f1 * (n1 - n0) / den : n1 + f1;
        if (!(std::abs(n2 - n1) <= 2.0 * std::abs(f1) + 1e-15)) n2 = n1 + f1;  // secant went astray
        n0 = n1;
        f0 = f1;
        n1 = n2;
      }
      // Strong birefringence at steep incidence makes g expand by (nγ − nα)·tanθ/n ≫ 1 and the
      // secant can wander off (a fuzzed nγ = 3 crystal at 82° once returned a non-root, and the
      // exit face then created 45 % power). h(n) = g(n) − n has exactly one root between n = q
      // (k_z = 0, where h = n_i(s) − q > 0 since every index exceeds q < 1) and n_max (h ≤ 0):
      // the line of constant tangential k meets each sheet of the index surface once on each side
      // (f(k_z) = det(ε + kkᵀ − k²I) is a quartic, positive at k_z = 0, with those four roots). So a
      // bracketed solve on [q, n_max] always finds the right mode.
      if (!converged && std::abs(f1) <= 1e-13) converged = true;  // rounding floor of g
      // Lower end k_z = 1e-12 rather than 0: at normal incidence (q = 0) the wave normal of
      // k_z = 0 is undefined.
      if (!converged || !(n1 >= std::sqrt(q2) && n1 <= n_max * (1 + 1e-12)))
        n1 = bracketed_mode_index(g, i, std::sqrt(q2 + 1e-24), n_max);
      mp.kz[i] = dir * kz_for(n1, q2);
    }
  }
  double gap = 1.0;  // smallest relative eigenvalue gap (λf − λs)/λf at the two wave normals
  for (int i = 0; i < 2; ++i) {
    mp.n[i] = std::sqrt(q2 + mp.kz[i] * mp.kz[i]);
    mp.s[i] = glm::dvec3(qx, qy, mp.kz[i]) / mp.n[i];
    const Eigen2 e = wave_normal_modes(P.eta, mp.s[i], s_hat);
    mp.dp[i] = i == 0 ? e.fx : -e.fy;
    mp.ds[i] = i == 0 ? e.fy : e.fx;
    gap = std::min(gap, (e.lam_fast - e.lam_slow) / e.lam_fast);
  }
  // Right-handed pair (det > 0) so that σ2 in the mode basis is a counter-clockwise rotation.
  double det = mp.dp[0] * mp.ds[1] - mp.ds[0] * mp.dp[1];
  if (det < 0.0) {
    mp.dp[1] = -mp.dp[1];
    mp.ds[1] = -mp.ds[1];
    det = -det;
  }
  // Next to an optic axis the D directions turn fast around it, and the two normals (which differ
  // by rounding there) can resolve them inconsistently. The modes are then nearly degenerate and
  // any orthogonal pair describes them: take the pair of the mean normal (det = 1). Only then:
  // away from an axis two well-separated normals legitimately carry skew D directions (each ⟂ its
  // own normal), and replacing them broke the face solutions' energy balance by up to 7 % for a
  // strongly birefringent crystal at 82° (fuzz finding regressions/plate_jones/F12_*). A gap of
  // 1e-6 leaves the eigenvectors good to ~1e-10 (rounding 1e-16 over the gap).
  if (det < 0.99 && gap < 1e-6) {
    const Eigen2 e = wave_normal_modes(P.eta, unit(glm::dvec3(qx, qy, 0.5 * (mp.kz[0] + mp.kz[1]))), s_hat);
    mp.dp[0] = e.fx;
    mp.ds[0] = e.fy;
    mp.dp[1] = -e.fy;
    mp.ds[1] = e.fx;
  }
  for (int i = 0; i < 2; ++i) mp.D[i] = mp.dp[i] * glm::cross(s_hat, mp.s[i]) + mp.ds[i] * s_hat;
  return mp;
}

// Tangential field (E_x, E_y, H_x, H_y) of a plane wave with wave vector k (units of k0) and
// field E; H = k × E in units of E/Z0 (Maxwell: k0·H·Z0 = k × E).
struct Tangential {
  double v[4];
};
inline Tangential tangential(const glm::dvec3& k, const glm::dvec3& E) {
  const glm::dvec3 H = glm::cross(k, E);
  return {{E.x, E.y, H.x, H.y}};
}

// Solves A·x = b for a 4×4 system given by columns, two right-hand sides; Gauss with pivoting.
void solve4(const Tangential cols[4], const Tangential rhs[2], double x[2][4]) {
  double m[4][6];
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m[r][c] = cols[c].v[r];
    m[r][4] = rhs[0].v[r];
    m[r][5] = rhs[1].v[r];
  }
  for (int c = 0; c < 4; ++c) {
    int piv = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(m[r][c]) > std::abs(m[piv][c])) piv = r;
    if (piv != c)
      for (int k = 0; k < 6; ++k) std::swap(m[c][k], m[piv][k]);
    const double inv = 1.0 / m[c][c];
    for (int r = c + 1; r < 4; ++r) {
      const double f = m[r][c] * inv;
      for (int k = c; k < 6; ++k) m[r][k] -= f * m[c][k];
    }
  }
  for (int j = 0; j < 2; ++j) {
    for (int r = 3; r >= 0; --r) {
      double acc = m[r][4 + j];
      for (int k = r + 1; k < 4; ++k) acc -= m[r][k] * x[j][k];
      x[j][r] = acc / m[r][r];
    }
  }
}

struct Solved {
  PlateModes m;
  double tin[2][2];   // mode amplitudes from (p, s) incident amplitudes: tin[mode][p|s]
  double tout[2][2];  // outgoing (p, s) amplitudes per unit mode amplitude: tout[p|s][mode]
  double kappa[2];    // amplitude attenuation exponents
  double alpha;       // optical rotation angle (rad, counter-clockwise positive)
  glm::dvec3 s_hat, p_air;
};

constexpr double kMaxKappa = 350.0;  // e^−350 ≈ 1e−152: opaque; keeps cosh(Im w) finite

Solved solve(const PreparedPlate& P, const glm::dvec3& k_air) {
  Solved out;
  PlateModes& m = out.m;
  const double qx = k_air.x, qy = k_air.y;
  const double q2 = qx * qx + qy * qy;
  // s_hat from (qx, qy) rescaled to their larger magnitude first: q² of q ~ 1e-158 is a denormal
  // with a few significant bits (fuzz finding F14), and q ~ 1e-320 is itself a denormal whose
  // quotients are good to 1e-5 only (F15); either left s_hat off unit length, and a lossless plate
  // then gained up to 2e-8.
  const double q_big = std::max(std::abs(qx), std::abs(qy));
  if (q_big > 0.0) {
    const double ux = qx / q_big, uy = qy / q_big, len = std::hypot(ux, uy);
    out.s_hat = glm::dvec3(-uy / len, ux / len, 0.0);
  } else {
    out.s_hat = glm::dvec3(0.0, 1.0, 0.0);
  }
  const glm::dvec3& s_hat = out.s_hat;
  out.p_air = glm::cross(s_hat, k_air);
  const double d = P.thickness_um;

  const ModePair f = find_modes(P, qx, qy, q2, s_hat, +1.0);
  if (!P.fresnel) {
    // Lossless: the mode D directions P = [[dp0, dp1], [ds0, ds1]] (columns, in (p, s)) are skew
    // at oblique incidence, and P⁻¹ … P would not be unitary (gains up to 9 % for calcite at
    // θ = 84°). Use the orthogonal matrix nearest to P (its polar factor) instead, so that
    // tin = Qᵀ, tout = Q and |J|² ≤ 1 to rounding. For 2×2 the polar factor is closed-form and
    // stable even for nearly parallel modes: a rotation by atan2(P10 − P01, P00 + P11) when
    // det P > 0, a reflection at atan2(P10 + P01, P00 − P11) otherwise.
    const double det = f.dp[0] * f.ds[1] - f.dp[1] * f.ds[0];
    double q00, q01, q10, q11;
    if (det >= 0.0) {
      const double t = std::atan2(f.ds[0] - f.dp[1], f.dp[0] + f.ds[1]);
      q00 = std::cos(t), q01 = -std::sin(t), q10 = std::sin(t), q11 = std::cos(t);
    } else {
      const double t = std::atan2(f.ds[0] + f.dp[1], f.dp[0] - f.ds[1]);
      q00 = std::cos(t), q01 = std::sin(t), q10 = std::sin(t), q11 = -std::cos(t);
    }
    out.tout[0][0] = q00;
    out.tout[0][1] = q01;
    out.tout[1][0] = q10;
    out.tout[1][1] = q11;
    out.tin[0][0] = q00;
    out.tin[0][1] = q10;
    out.tin[1][0] = q01;
    out.tin[1][1] = q11;
  } else {
    const ModePair b = find_modes(P, qx, qy, q2, s_hat, -1.0);
    // Grazing in the outer medium (k_z → 0): incident and reflected waves coincide and nothing
    // enters; a floor keeps the face systems regular (transmission → 0 continuously).
    const double kzm = std::max(kz_for(P.n_outside, q2), 1e-12);
    const glm::dvec3 kf(qx, qy, kzm), kr(qx, qy, -kzm);
    const glm::dvec3 pf = glm::cross(s_hat, kf / P.n_outside), pr = glm::cross(s_hat, kr / P.n_outside);
    Tangential mode_f[2], mode_b[2];
    for (int i = 0; i < 2; ++i) {
      // Forward modes normalised to unit power flux S_z = (E × H)_z, so that the mode amplitudes
      // are power amplitudes and the unitary bulk matrix N (optical activity) conserves energy.
      const glm::dvec3 kf_i(qx, qy, f.kz[i]);
      const glm::dvec3 E = P.eta * f.D[i];  // E = η·D
      const double Sz = glm::cross(E, glm::cross(kf_i, E)).z;
      mode_f[i] = tangential(kf_i, E / std::sqrt(std::max(Sz, 1e-300)));
      mode_b[i] = tangential(glm::dvec3(qx, qy, b.kz[i]), P.eta * b.D[i]);
    }
    auto neg = [](Tangential t) {
      for (double& v : t.v) v = -v;
      return t;
    };
    // Entry: a1·ψ1 + a2·ψ2 − r_p·ψ_rp − r_s·ψ_rs = ψ_inc, for incident p and s.
    const Tangential in_cols[4] = {mode_f[0], mode_f[1], neg(tangential(kr, pr)), neg(tangential(kr, s_hat))};
    const Tangential in_rhs[2] = {tangential(kf, pf), tangential(kf, s_hat)};
    double xin[2][4];
    solve4(in_cols, in_rhs, xin);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) out.tin[i][j] = xin[j][i];
    // Exit: t_p·ψ_tp + t_s·ψ_ts − b1·ψ_b1 − b2·ψ_b2 = ψ_mode, for each forward mode.
    const Tangential out_cols[4] = {tangential(kf, pf), tangential(kf, s_hat), neg(mode_b[0]),
                                    neg(mode_b[1])};
    double xout[2][4];
    solve4(out_cols, mode_f, xout);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) out.tout[i][j] = xout[j][i];
  }

  for (int i = 0; i < 2; ++i) {
    const double ci = f.s[i].z;
    double kappa = 0.0;
    if (P.absorbing) kappa = std::min(0.5 * glm::dot(f.D[i], P.mu_tensor * f.D[i]) * d / ci, kMaxKappa);
    out.kappa[i] = kappa;
    // Poynting direction E × (k × E) = k|E|² − E(E·k), E = η·D (Born & Wolf §15.2).
    const glm::dvec3 E = P.eta * f.D[i];
    const glm::dvec3 ray = f.s[i] * glm::dot(E, E) - E * glm::dot(E, f.s[i]);
    (i == 0 ? m.walkoff1 : m.walkoff2) = glm::dvec3(ray.x, ray.y, 0.0) * (d / ray.z);
    // Mode transmission: a wave polarized along the mode's (p, s) direction, through mode i only.
    const double a = out.tin[i][0] * f.dp[i] + out.tin[i][1] * f.ds[i];
    const double t = std::sqrt(out.tout[0][i] * out.tout[0][i] + out.tout[1][i] * out.tout[1][i]) *
                     std::abs(a) * amplitude_attenuation(kappa);  // 0 when opaque (beer_lambert.h)
    (i == 0 ? m.t1 : m.t2) = t;
    (i == 0 ? m.e1 : m.e2) = f.dp[i] * out.p_air + f.ds[i] * s_hat;
  }
  m.n1 = f.n[0];
  m.n2 = f.n[1];
  m.kz1 = f.kz[0];
  m.kz2 = f.kz[1];
  m.s1 = f.s[0];
  m.s2 = f.s[1];
  m.retardation_nm = std::max(f.kz[1] - f.kz[0], 0.0) * d * 1e3;
  m.mean_phase_rad = P.k0_per_um * d * 0.5 * (f.kz[0] + f.kz[1]);
  out.alpha = 0.0;
  if (P.rho_rad_per_um != 0.0) {
    const glm::dvec3 s_mean = unit(glm::dvec3(qx, qy, 0.5 * (f.kz[0] + f.kz[1])));
    const double cos_c = glm::dot(s_mean, P.optic_axis);
    out.alpha = -P.rho_rad_per_um * cos_c * cos_c * d / s_mean.z;
  }
  return out;
}

}  // namespace

PlateModes plate_modes(const PreparedPlate& plate, const glm::dvec3& k_air) { return solve(plate, k_air).m; }

PlateModes plate_modes(const PlateSpec& plate, const glm::dvec3& k_air, double wavelength_nm) {
  return plate_modes(prepare_plate(plate, wavelength_nm), k_air);
}

JonesMatrix plate_jones(const PreparedPlate& plate, const glm::dvec3& k_air) {
  const Solved s = solve(plate, k_air);
  const double delta = plate.k0_per_um * plate.thickness_um * (s.m.kz2 - s.m.kz1);
  // Bulk propagation in the mode basis: N = exp(−iH), H = h0·I + h3·σ3 + h2·σ2 (σ2 = [[0,−i],[i,0]]),
  // exp(−iH) = e^{−ih0}[cos w·I − i·(sin w/w)·(h3σ3 + h2σ2)], w = √(h3² + h2²) (Jones 1948).
  const complexd I(0.0, 1.0);
  const complexd h0 = -0.5 * I * (s.kappa[0] + s.kappa[1]);
  const complexd h3 = 0.5 * delta - 0.5 * I * (s.kappa[0] - s.kappa[1]);
  const double h2 = s.alpha;
  complexd n11, n12, n21, n22;
  if (h2 == 0.0) {
    // Linear modes: diag(e^{−κ1}·e^{−iδ/2}, e^{−κ2}·e^{+iδ/2}).
    const double c = std::cos(0.5 * delta), sn = std::sin(0.5 * delta);
    // An opaque mode (magnetite, ilmenite) passes exactly nothing: no subnormal floats downstream.
    const double g1 = s.kappa[0] != 0.0 ? amplitude_attenuation(s.kappa[0]) : 1.0;
    const double g2 = s.kappa[1] != 0.0 ? amplitude_attenuation(s.kappa[1]) : 1.0;
    n11 = complexd(g1 * c, -g1 * sn);
    n22 = complexd(g2 * c, g2 * sn);
    n12 = n21 = 0.0;
  } else {
    const complexd w = std::sqrt(h3 * h3 + h2 * h2);
    const complexd S = std::abs(w) < 1e-6 ? 1.0 - w * w / 6.0 : std::sin(w) / w;
    const complexd cw = std::cos(w), e0 = std::exp(-I * h0);
    n11 = e0 * (cw - I * S * h3);
    n22 = e0 * (cw + I * S * h3);
    n12 = -e0 * S * h2;
    n21 = e0 * S * h2;
  }
  // J_ps = T_out · N · T_in.
  const complexd a00 = n11 * s.tin[0][0] + n12 * s.tin[1][0], a01 = n11 * s.tin[0][1] + n12 * s.tin[1][1];
  const complexd a10 = n21 * s.tin[0][0] + n22 * s.tin[1][0], a11 = n21 * s.tin[0][1] + n22 * s.tin[1][1];
  const JonesMatrix Jps{s.tout[0][0] * a00 + s.tout[0][1] * a10, s.tout[0][0] * a01 + s.tout[0][1] * a11,
                        s.tout[1][0] * a00 + s.tout[1][1] * a10, s.tout[1][0] * a01 + s.tout[1][1] * a11};
  // Change of basis (a, b) of k_air → (p, s): C = [[p·a, p·b], [s·a, s·b]]; J_ab = Cᵀ·J_ps·C.
  glm::dvec3 a, b;
  transverse_basis(k_air, a, b);
  const double c00 = glm::dot(s.p_air, a), c01 = glm::dot(s.p_air, b);
  const double c10 = glm::dot(s.s_hat, a), c11 = glm::dot(s.s_hat, b);
  const JonesMatrix C{c00, c01, c10, c11}, CT{c00, c10, c01, c11};
  return CT * Jps * C;
}

JonesMatrix plate_jones(const PlateSpec& plate, const glm::dvec3& k_air, double wavelength_nm) {
  return plate_jones(prepare_plate(plate, wavelength_nm), k_air);
}

}  // namespace pmsim
