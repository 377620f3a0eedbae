#pragma once
// The paper's transformation G (§6): a linearly polarized ray meets the interface between two
// isotropic media and leaves as a reflected and a refracted ray, each again linearly polarized.
// Under total internal reflection the reflected light is elliptically polarized; following the
// paper it is returned as two linearly polarized rays (the E⊥ and E∥ parts) with their δ.
// No heap allocation: results go into a caller-owned fixed-size struct.
#include <cmath>
#include <glm/geometric.hpp>

#include "core/optics/fresnel.h"
#include "core/optics/interface_model.h"
#include "core/optics/polarization_frame.h"
#include "core/optics/polarized_ray.h"
#include "core/optics/schlick.h"

namespace pmsim {

struct InteractionResult {
  PolarizedRay reflected[2];  // [0] only, or under TIR: [0] = E⊥ part, [1] = E∥ part
  int reflected_count = 0;    // components of zero intensity are left out
  PolarizedRay refracted;
  bool has_refracted = false;  // false under TIR or when its intensity is 0
  bool tir = false;
  glm::dvec3 reflected_dir{0.0}, refracted_dir{0.0};
  FresnelAmplitudes amplitudes;
  double reflected_intensity() const {
    double s = 0.0;
    for (int k = 0; k < reflected_count; ++k) s += reflected[k].intensity;
    return s;
  }
};

// Mirror direction r = d − 2(d·N)N.
inline glm::dvec3 reflect_dir(const glm::dvec3& d, const glm::dvec3& N) {
  return d - 2.0 * glm::dot(d, N) * N;
}

// Refracted direction, vector Snell law t = d/η + (cosθi/η − cosθt)·N_f with N_f facing the
// incident ray (cosθi = −d·N_f > 0); η = n_t/n_i.
inline glm::dvec3 refract_dir(const glm::dvec3& d, const glm::dvec3& N_facing, double cos_i, double cos_t,
                              double eta) {
  return glm::normalize(d / eta + (cos_i / eta - cos_t) * N_facing);
}

// G at `point` with unit normal `normal` (either orientation); n_i on the side the ray comes from,
// n_t on the other. Outgoing rays start at `point` and inherit λ, δ, O_p, ch and depth from `in`
// (the caller adds the path it owns and sets depth). Field of a ray: √I·v_p·e^(−iδ).
inline void interact(const PolarizedRay& in, const glm::dvec3& point, const glm::dvec3& normal, double n_i,
                     double n_t, FresnelModel model, InteractionResult& out) {
  const glm::dvec3& d = in.dir;
  double dn = glm::dot(d, normal);
  const glm::dvec3 N_f = dn > 0.0 ? -normal : normal;  // faces the incident ray
  const double cos_i = std::min(1.0, std::abs(dn));
  const double eta = n_t / n_i;
  const FresnelAmplitudes f =
      model == FresnelModel::Schlick ? schlick_amplitudes(cos_i, eta) : fresnel_amplitudes(cos_i, eta);
  out.amplitudes = f;
  out.tir = f.tir;
  out.reflected_count = 0;
  out.has_refracted = false;

  const PolarizationFrame fr = polarization_frame(d, N_f);
  const double a_s = glm::dot(in.pol, fr.s);
  const double a_p = glm::dot(in.pol, fr.p_i);
  const glm::dvec3 r = glm::normalize(reflect_dir(d, N_f));
  const glm::dvec3 p_r = p_reflected(fr.s, r);
  out.reflected_dir = r;

  auto emit_reflected = [&](double intensity, const glm::dvec3& pol, double delta) {
    if (!(intensity > 0.0)) return;
    PolarizedRay& o = out.reflected[out.reflected_count++];
    o = in;
    o.origin = point;
    o.dir = r;
    o.pol = pol;
    o.intensity = intensity;
    o.delta_rad = delta;
  };

  if (f.tir) {
    // Paper §6: E_r⊥ = E⊥, E_r∥ = E∥ in modulus; phases δ⊥, δ∥. Two linear rays.
    emit_reflected(in.intensity * a_s * a_s, (a_s < 0.0 ? -1.0 : 1.0) * fr.s, in.delta_rad - std::arg(f.r_s));
    emit_reflected(in.intensity * a_p * a_p, (a_p < 0.0 ? -1.0 : 1.0) * p_r, in.delta_rad - std::arg(f.r_p));
    return;
  }

  // Real amplitudes: a negative ratio is the paper's −π jump, carried by the sign of v_p.
  const double rs = f.r_s.real(), rp = f.r_p.real();
  const glm::dvec3 Er = (rs * a_s) * fr.s + (rp * a_p) * p_r;
  const double er2 = rs * rs * a_s * a_s + rp * rp * a_p * a_p;
  if (er2 > 0.0) emit_reflected(in.intensity * er2, Er / std::sqrt(er2), in.delta_rad);

  const glm::dvec3 t = refract_dir(d, N_f, f.cos_i, f.cos_t, f.eta);
  out.refracted_dir = t;
  const glm::dvec3 p_t = p_refracted(fr.s, t);
  const glm::dvec3 Et = (f.t_s * a_s) * fr.s + (f.t_p * a_p) * p_t;
  const double et2 = f.t_s * f.t_s * a_s * a_s + f.t_p * f.t_p * a_p * a_p;
  const double It = in.intensity * f.power_factor() * et2;  // T = (n_t cosθt/n_i cosθi)|t|²
  if (It > 0.0) {
    PolarizedRay& o = out.refracted;
    o = in;
    o.origin = point;
    o.dir = t;
    o.pol = Et / std::sqrt(et2);
    o.intensity = It;
    out.has_refracted = true;  // refraction is co-phased (paper §6): δ unchanged
  }
}

}  // namespace pmsim
