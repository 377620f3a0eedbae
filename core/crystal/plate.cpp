// Plane-wave eigenmodes of an anisotropic plate and its Jones matrix.
//
// Model and approximations (after Debelov & Kozlov 2013, Born & Wolf §15.2–15.3, Yariv & Yeh ch. 4):
// * The incident wave has tangential wave vector q = k0·(k_air.x, k_air.y) (conserved through the
//   mounting medium, the plate and back). Inside the crystal each eigenmode has wave normal
//   s_i = (q, k_zi)/n_i with n_i its index for that normal: the Fresnel equation of wave normals
//   is solved as the 2×2 eigenproblem of the impermeability tensor η = ε⁻¹ projected on the
//   plane ⟂ s (eigenvalues 1/n², eigenvectors the D directions). Uniaxial: k_z in closed form
//   (ordinary k_z = √(no² − q²); extraordinary from the quadratic kᵀAk = 1 with
//   A = I/ne² + (1/no² − 1/ne²)ccᵀ). Biaxial: the fixed point n ← n(s(n)) for each mode, which
//   contracts by about (nγ − nα)·tanθ/n per step and is iterated to 1e-15.
// * The interfaces use, for each mode, the isotropic Fresnel amplitudes (Born & Wolf 1.5 (20))
//   for the mode's own index and angle, weighted by its TE/TM content d_p², d_s². This is exact
//   for modes that are pure TE or TM and first-order in the birefringence otherwise; it ignores
//   the coupling of the two modes at the faces and multiple reflections inside the plate.
//   At normal incidence t_in·t_out = 4n n'/(n + n')² = 1 − R.
// * Mode fields are carried in TE/TM coordinates: the same (p, s) components map a field in the
//   crystal (relative to s_i) to one outside (relative to k_air), with s = unit(ẑ × k) and
//   p = s × k. The two mode columns may be non-orthogonal; the incident field is decomposed with
//   the inverse of that basis.
// * Absorption (pleochroism): a mode vibrating along D loses intensity at μ = Dᵀ·M·D with
//   M = Σ μ_k·axis_k·axis_kᵀ (the principal absorptions weighted by (D·axis_k)²), over the path
//   d/cos θ_i; the lossless mode shapes are kept (weak absorption).
// * Optical activity: the plate acts on the two modes as exp(−iH), H = (δ/2)σ3 + α σ2 + absorption,
//   Jones' N-matrix combination of linear retardance δ = k0·d·(k_z2 − k_z1) and a rotation
//   α = −ρ·(s·c)²·d/cos θ (gyration along the wave normal ∝ cos² of its angle to the optic axis;
//   the transverse gyration component g11 is neglected). Along the axis this is a pure rotation
//   by ρd; far from it the linear birefringence dominates and the modes become linear again.
// * Walk-off: the lateral ray displacement is reported in PlateModes but not applied: across a
//   30 µm section it is below 2 µm, much less than a pixel of a thin-section image.
#include "core/crystal/plate.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

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
  p.k0_per_um = 2.0 * std::numbers::pi / (wavelength_nm * 1e-3);
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

// Symmetric 2×2 [[a, b], [b, c]] — closed form; at degeneracy any orthogonal pair (here p, s).
inline Eigen2 eigen_sym2(double a, double b, double c) {
  const double m = 0.5 * (a + c), h = 0.5 * (a - c);
  const double r = std::hypot(h, b);
  Eigen2 e{m + r, m - r, 1.0, 0.0};
  if (r > 0.0) {
    double x, y;
    if (h >= 0.0) { x = h + r; y = b; } else { x = b; y = r - h; }
    const double len = std::hypot(x, y);
    e.fx = x / len;
    e.fy = y / len;
  }
  return e;
}

inline double quad(const glm::dmat3& M, const glm::dvec3& u, const glm::dvec3& v) {
  return glm::dot(u, M * v);
}

// η projected on the plane ⟂ s, in the basis (p = s_hat × s, s_hat).
inline Eigen2 wave_normal_modes(const glm::dmat3& eta, const glm::dvec3& s, const glm::dvec3& s_hat) {
  const glm::dvec3 p = glm::cross(s_hat, s);
  const glm::dvec3 eta_p = eta * p, eta_s = eta * s_hat;
  return eigen_sym2(glm::dot(p, eta_p), glm::dot(p, eta_s), glm::dot(s_hat, eta_s));
}

inline glm::dvec3 normal_from(double qx, double qy, double kz) {
  return glm::dvec3(qx, qy, kz) / std::sqrt(qx * qx + qy * qy + kz * kz);
}

inline double kz_for(double n, double q2) { return std::sqrt(std::max(n * n - q2, 0.0)); }

// Isotropic Fresnel amplitude transmissions (Born & Wolf 1.5 (20)):
// t_s = 2n1c1/(n1c1 + n2c2), t_p = 2n1c1/(n2c1 + n1c2).
inline double t_s(double n1, double c1, double n2, double c2) { return 2 * n1 * c1 / (n1 * c1 + n2 * c2); }
inline double t_p(double n1, double c1, double n2, double c2) { return 2 * n1 * c1 / (n2 * c1 + n1 * c2); }

struct Solved {
  PlateModes m;
  double dp[2], ds[2];  // mode D directions in TE/TM coordinates (columns of P)
  double kappa[2];      // amplitude attenuation exponents
  double alpha;         // optical rotation angle (rad, counter-clockwise positive)
  double fresnel_t[2];  // t_in·t_out of each mode (1 without Fresnel)
  glm::dvec3 s_hat, p_air;
};

constexpr double kMaxKappa = 350.0;  // e^−350 ≈ 1e−152: opaque; keeps cosh(Im w) finite

Solved solve(const PreparedPlate& P, const glm::dvec3& k_air) {
  Solved out;
  PlateModes& m = out.m;
  const double qx = k_air.x, qy = k_air.y;
  const double q2 = qx * qx + qy * qy;
  const double q = std::sqrt(q2);
  out.s_hat = q > 0.0 ? glm::dvec3(-qy / q, qx / q, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  const glm::dvec3& s_hat = out.s_hat;
  out.p_air = glm::cross(s_hat, k_air);

  // Normal components k_z (units of k0) of the fast (index 0) and slow (1) modes.
  double kz[2];
  if (P.symmetry == CrystalSymmetry::Uniaxial) {
    const double no = P.n_principal.x, ne = P.n_principal.z;
    const glm::dvec3& c = P.optic_axis;
    const double kzo = kz_for(no, q2);
    // kᵀAk = 1, A = I/ne² + (1/no² − 1/ne²)ccᵀ (extraordinary wave normals, Born & Wolf §15.3.3).
    const double g = 1.0 / (no * no) - 1.0 / (ne * ne), ie2 = 1.0 / (ne * ne);
    const double a = ie2 + g * c.z * c.z;
    const double b = 2.0 * g * c.z * (c.x * qx + c.y * qy);
    const double cq = c.x * qx + c.y * qy;
    const double c0 = ie2 * q2 + g * cq * cq - 1.0;
    const double disc = std::sqrt(std::max(b * b - 4.0 * a * c0, 0.0));
    // Forward root, written without cancellation (c0 < 0 ⇒ one positive root).
    const double kze = b >= 0.0 ? (2.0 * c0) / (-b - disc) : (-b + disc) / (2.0 * a);
    const double n_e_eff = std::sqrt(q2 + kze * kze);
    if (no <= n_e_eff) { kz[0] = kzo; kz[1] = kze; } else { kz[0] = kze; kz[1] = kzo; }
  } else {
    for (int i = 0; i < 2; ++i) {
      double n = P.mean_n;
      for (int it = 0; it < 60; ++it) {
        const Eigen2 e = wave_normal_modes(P.eta, normal_from(qx, qy, kz_for(n, q2)), s_hat);
        const double n_new = 1.0 / std::sqrt(i == 0 ? e.lam_fast : e.lam_slow);
        const double diff = std::abs(n_new - n);
        n = n_new;
        if (diff <= 1e-15) break;
      }
      kz[i] = kz_for(n, q2);
    }
  }

  // Mode fields at each mode's own wave normal; the fast one is the larger-η eigenvector.
  const double kzm = kz_for(P.n_outside, q2);
  const double cm = kzm / P.n_outside;
  const double d = P.thickness_um;
  double t_total[2];
  glm::dvec3 s_i[2];
  for (int i = 0; i < 2; ++i) {
    s_i[i] = normal_from(qx, qy, kz[i]);
    const Eigen2 e = wave_normal_modes(P.eta, s_i[i], s_hat);
    out.dp[i] = i == 0 ? e.fx : -e.fy;
    out.ds[i] = i == 0 ? e.fy : e.fx;
    const double n = std::sqrt(q2 + kz[i] * kz[i]);
    const double ci = kz[i] / n;
    const double dp2 = out.dp[i] * out.dp[i], ds2 = out.ds[i] * out.ds[i];
    double t = 1.0;
    if (P.fresnel) {
      const double tin = dp2 * t_p(P.n_outside, cm, n, ci) + ds2 * t_s(P.n_outside, cm, n, ci);
      const double tout = dp2 * t_p(n, ci, P.n_outside, cm) + ds2 * t_s(n, ci, P.n_outside, cm);
      t = tin * tout;
    }
    const glm::dvec3 p_i = glm::cross(s_hat, s_i[i]);
    const glm::dvec3 D = out.dp[i] * p_i + out.ds[i] * s_hat;
    double kappa = 0.0;
    if (P.absorbing) kappa = std::min(0.5 * quad(P.mu_tensor, D, D) * d / ci, kMaxKappa);
    out.kappa[i] = kappa;
    t_total[i] = t;
    (i == 0 ? m.n1 : m.n2) = n;
    (i == 0 ? m.e1 : m.e2) = out.dp[i] * out.p_air + out.ds[i] * s_hat;
    // Poynting direction E × (k × E) = k|E|² − E(E·k), E = η·D (Born & Wolf §15.2).
    const glm::dvec3 E = P.eta * D;
    const glm::dvec3 ray = s_i[i] * glm::dot(E, E) - E * glm::dot(E, s_i[i]);
    (i == 0 ? m.walkoff1 : m.walkoff2) = glm::dvec3(ray.x, ray.y, 0.0) * (d / ray.z);
  }
  // Right-handed mode pair (det P > 0) so that σ2 below means a counter-clockwise rotation.
  if (out.dp[0] * out.ds[1] - out.ds[0] * out.dp[1] < 0.0) {
    out.dp[1] = -out.dp[1];
    out.ds[1] = -out.ds[1];
    m.e2 = -m.e2;
  }
  m.kz1 = kz[0];
  m.kz2 = kz[1];
  m.s1 = s_i[0];
  m.s2 = s_i[1];
  m.t1 = t_total[0] * std::exp(-out.kappa[0]);
  m.t2 = t_total[1] * std::exp(-out.kappa[1]);
  m.retardation_nm = std::max(kz[1] - kz[0], 0.0) * d * 1e3;
  m.mean_phase_rad = P.k0_per_um * d * 0.5 * (kz[0] + kz[1]);
  out.alpha = 0.0;
  if (P.rho_rad_per_um != 0.0) {
    const glm::dvec3 s_mean = normal_from(qx, qy, 0.5 * (kz[0] + kz[1]));
    const double cos_c = glm::dot(s_mean, P.optic_axis);
    out.alpha = -P.rho_rad_per_um * cos_c * cos_c * d / s_mean.z;
  }
  out.fresnel_t[0] = t_total[0];
  out.fresnel_t[1] = t_total[1];
  return out;
}

}  // namespace

PlateModes plate_modes(const PreparedPlate& plate, const glm::dvec3& k_air) {
  return solve(plate, k_air).m;
}

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
    n11 = std::exp(-I * (h0 + h3));
    n22 = std::exp(-I * (h0 - h3));
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
  // J_ps = P · diag(t) · N · P⁻¹ with P = [[dp0, dp1], [ds0, ds1]] (the Fresnel products t_in·t_out
  // of a mode are applied on its own column; for N diagonal this is exact within the model).
  const double t0 = s.fresnel_t[0], t1 = s.fresnel_t[1];
  const double det = s.dp[0] * s.ds[1] - s.dp[1] * s.ds[0];
  const double i00 = s.ds[1] / det, i01 = -s.dp[1] / det, i10 = -s.ds[0] / det, i11 = s.dp[0] / det;
  const complexd a00 = t0 * n11, a01 = t0 * n12, a10 = t1 * n21, a11 = t1 * n22;  // diag(t)·N
  const complexd b00 = a00 * i00 + a01 * i10, b01 = a00 * i01 + a01 * i11;      // ·P⁻¹
  const complexd b10 = a10 * i00 + a11 * i10, b11 = a10 * i01 + a11 * i11;
  const JonesMatrix Jps{s.dp[0] * b00 + s.dp[1] * b10, s.dp[0] * b01 + s.dp[1] * b11,
                        s.ds[0] * b00 + s.ds[1] * b10, s.ds[0] * b01 + s.ds[1] * b11};
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
