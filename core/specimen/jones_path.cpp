#include "core/specimen/jones_path.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/base/units.h"
#include "core/crystal/section_optics.h"
#include "core/optics/fresnel.h"
#include "core/optics/interaction.h"

namespace pmsim {

namespace {

using cd = std::complex<double>;

struct CVec {  // a complex 3-vector: the transverse field
  cd x, y, z;
};
CVec operator*(cd a, const CVec& v) { return {a * v.x, a * v.y, a * v.z}; }
CVec operator+(const CVec& a, const CVec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
CVec real_vec(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
// Bilinear product with a real vector (the component along it; no conjugation).
cd dot(const glm::dvec3& r, const CVec& v) { return r.x * v.x + r.y * v.y + r.z * v.z; }
double power(const CVec& v) { return std::norm(v.x) + std::norm(v.y) + std::norm(v.z); }

struct Branch {
  glm::dvec3 origin{0.0}, dir{0.0};
  int medium = kSpecimenAir;
  double n = 1.0;               // index of this wave (a crystal mode's n_k along dir)
  glm::dvec3 mode{0.0};         // crystal: the mode's vibration e_k; unused in isotropic media
  bool crystal_mode = false;
  CVec E[2];                    // fields per start vibration, without the bulk phase
  double phase_rad = 0.0;       // k0·Σ n·L (+ the exit term), unwrapped
  int events = 0;
};

// s = unit(d × N) (fresnel.h's frame), any unit ⟂ d at normal incidence.
glm::dvec3 s_axis(const glm::dvec3& d, const glm::dvec3& N) {
  const glm::dvec3 s = glm::cross(d, N);
  const double l = glm::length(s);
  if (l > 1e-12) return s / l;
  const glm::dvec3 ref = std::abs(d.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(d, ref));
}

struct Mode {
  bool ok = false;
  glm::dvec3 dir{0.0}, vib{0.0};
  double n = 1.0;
  FresnelAmplitudes f;
};

// Mode k (0 fast, 1 slow) refracted into crystal `c` (axes R) from a wave of index n_i along d:
// Snell with the direction-dependent index, by fixed-point iteration (the index changes with the
// angle by ≲ the birefringence, so each step shrinks the error by ~Δn·tanθ: 6 steps are exact to
// double for any mineral).
Mode refract_mode(const glm::dmat3& R, const glm::dvec3& n_xyz, int k, const glm::dvec3& d,
                  const glm::dvec3& N_f, double cos_i, double n_i) {
  Mode m;
  glm::dvec3 t = d;
  for (int it = 0; it < 6; ++it) {
    const SectionOptics so = section_optics(R, n_xyz, t);
    m.n = k == 0 ? so.n_fast : so.n_slow;
    const double eta = m.n / n_i;
    const double ct2 = snell_cos_t2(cos_i, eta);
    if (ct2 < 0.0) return m;  // evanescent (m.n: the index it would have)
    t = refract_dir(d, N_f, cos_i, std::sqrt(ct2), eta);
  }
  const SectionOptics so = section_optics(R, n_xyz, t);
  m.n = k == 0 ? so.n_fast : so.n_slow;
  m.vib = k == 0 ? so.fast : so.slow;
  m.f = fresnel_amplitudes(cos_i, m.n / n_i);
  if (m.f.tir) return m;
  m.dir = refract_dir(d, N_f, cos_i, m.f.cos_t, m.f.eta);
  m.ok = true;
  return m;
}

void count_event(InterfaceCounters* c, double incident, double reflected, double transmitted, bool tir) {
  if (!c) return;
  ++c->events;
  c->tir += tir ? 1 : 0;
  c->incident += incident;
  c->reflected += reflected;
  c->transmitted += transmitted;
  if (incident > 1e-300)
    c->max_defect = std::max(c->max_defect, std::abs(incident - reflected - transmitted) / incident);
}

}  // namespace

JonesPath trace_specimen_jones(const SpecimenScene& scene, const JonesPathRequest& q, InterfaceCounters* counters) {
  JonesPath out;
  if (counters) ++counters->paths;
  const double lambda = q.wavelength_nm;
  const double k0 = 2.0 * kPi / (lambda * 1e-3);  // per µm
  const int starts = q.starts > 1 ? 2 : 1;

  Branch b0;
  b0.dir = glm::normalize(q.dir);
  b0.origin = q.origin;
  b0.medium = kSpecimenAir;
  b0.n = scene.index(kSpecimenAir, lambda, b0.dir);
  glm::dvec3 a = q.start_vibration - glm::dot(q.start_vibration, b0.dir) * b0.dir;
  a = glm::length(a) > 1e-12 ? glm::normalize(a) : s_axis(b0.dir, glm::dvec3(0, 0, 1));
  b0.E[0] = real_vec(a);
  b0.E[1] = real_vec(glm::cross(b0.dir, a));
  const glm::dvec3 x_start = q.origin;

  std::array<Branch, 2 * kMaxJonesLeaves> stack;
  int top = 0;
  stack[top++] = b0;
  int branches = 1;  // leaves of the tree so far (live + ended)
  SpecimenHit hit;
  const auto field_power = [starts](const Branch& b) {
    return power(b.E[0]) + (starts > 1 ? power(b.E[1]) : 0.0);
  };

  while (top > 0) {
    Branch b = stack[--top];
    for (;;) {
      if (b.events >= q.max_interfaces) {
        if (counters) ++counters->lost;
        ++out.leaves;
        break;
      }
      if (!scene.intersect(b.origin, b.dir, 0.0, hit)) {
        ++out.leaves;
        const double sin_exit = std::sqrt(b.dir.x * b.dir.x + b.dir.y * b.dir.y);
        if (b.medium == kSpecimenAir && b.dir.z < 0.0 && sin_exit <= q.condenser_sin_max) {
          ++out.lit;
          glm::dvec3 p = q.polarizer - glm::dot(q.polarizer, b.dir) * b.dir;
          const double pl = glm::length(p);
          if (pl > 1e-12) {
            p /= pl;
            // The plane wave arriving along the branch: its phase at the exit point.
            const double phase = b.phase_rad - k0 * b.n * glm::dot(b.dir, b.origin - x_start);
            const cd e = std::polar(1.0, phase);
            for (int s = 0; s < starts; ++s) out.amplitude[s] += e * dot(p, b.E[s]);
          }
        }
        break;
      }
      // Bulk: phase and pleochroic attenuation along the segment.
      b.phase_rad += k0 * b.n * hit.t;
      if (b.crystal_mode) {
        const Crystal* c = scene.crystal_of(b.medium);
        if (c && c->absorbing()) {
          const glm::dvec3 mu = c->principal_absorption_per_um(lambda);
          const glm::dmat3 R = scene.orientation_of(b.medium);
          const double ex = glm::dot(b.mode, R[0]), ey = glm::dot(b.mode, R[1]), ez = glm::dot(b.mode, R[2]);
          const double att = std::exp(-0.5 * (mu.x * ex * ex + mu.y * ey * ey + mu.z * ez * ez) * hit.t);
          for (int s = 0; s < starts; ++s) b.E[s] = cd(att) * b.E[s];
        }
      }
      ++b.events;
      ++out.interfaces;
      const bool from_front = glm::dot(b.dir, hit.normal) < 0.0;
      const int from = from_front ? hit.front : hit.back;
      const int to = from_front ? hit.back : hit.front;
      const glm::dvec3 N_f = from_front ? hit.normal : -hit.normal;  // faces the incident ray
      const double cos_i = std::min(1.0, std::abs(glm::dot(b.dir, hit.normal)));
      const glm::dvec3 d = b.dir;
      const glm::dvec3 s = s_axis(d, hit.normal);
      const glm::dvec3 p_i = glm::cross(d, s);
      cd Es[2], Ep[2];
      for (int k = 0; k < starts; ++k) {
        Es[k] = dot(s, b.E[k]);
        Ep[k] = dot(p_i, b.E[k]);
      }
      const double incident = field_power(b);
      const Crystal* to_crystal = scene.crystal_of(to);
      const Crystal* from_crystal = scene.crystal_of(from);
      const auto offset = [&](const glm::dvec3& dir) {
        return hit.point + (glm::dot(dir, hit.normal) > 0.0 ? 1e-3 : -1e-3) * hit.normal;
      };
      // Reflection under TIR: mirror direction, r_s, r_p with their phases; inside a crystal the
      // reflected field is split again into its modes.
      const auto reflect_tir = [&](const FresnelAmplitudes& f) {
        const glm::dvec3 r = reflect_dir(d, hit.normal);
        const glm::dvec3 p_r = glm::cross(s, r);
        for (int k = 0; k < starts; ++k) b.E[k] = (f.r_s * Es[k]) * real_vec(s) + (f.r_p * Ep[k]) * real_vec(p_r);
        b.dir = r;
        b.origin = offset(r);
        b.medium = from;
        if (!from_crystal) return;
        const glm::dmat3 R = scene.orientation_of(from);
        const glm::dvec3 n_xyz = from_crystal->principal_indices(lambda);
        const SectionOptics so = section_optics(R, n_xyz, r);
        Branch m[2] = {b, b};
        for (int k = 0; k < 2; ++k) {
          m[k].mode = k == 0 ? so.fast : so.slow;
          m[k].n = k == 0 ? so.n_fast : so.n_slow;
          m[k].crystal_mode = true;
          for (int j = 0; j < starts; ++j) m[k].E[j] = dot(m[k].mode, b.E[j]) * real_vec(m[k].mode);
        }
        if (branches < kMaxJonesLeaves && top < int(stack.size())) {
          ++branches;
          stack[top++] = m[1];
          b = m[0];
        } else {
          const int keep = field_power(m[0]) >= field_power(m[1]) ? 0 : 1;
          if (counters) counters->capped_power += field_power(m[1 - keep]);
          b = m[keep];
        }
      };

      if (!to_crystal) {
        const double n_t = scene.index(to, lambda, d);
        const FresnelAmplitudes f = fresnel_amplitudes(cos_i, n_t / b.n);
        if (f.tir) {
          count_event(counters, incident, incident, 0.0, true);
          reflect_tir(f);
          continue;
        }
        const double g = std::sqrt(f.power_factor());
        const glm::dvec3 t = refract_dir(d, N_f, cos_i, f.cos_t, f.eta);
        const glm::dvec3 p_t = glm::cross(t, s);
        double reflected = 0.0;
        for (int k = 0; k < starts; ++k) {
          reflected += f.R_s() * std::norm(Es[k]) + f.R_p() * std::norm(Ep[k]);
          b.E[k] = (g * f.t_s * Es[k]) * real_vec(s) + (g * f.t_p * Ep[k]) * real_vec(p_t);
        }
        count_event(counters, incident, reflected, field_power(b), false);
        b.dir = t;
        b.n = n_t;
        b.medium = to;
        b.crystal_mode = false;
        b.origin = offset(t);
        continue;
      }

      // Into a crystal: one branch per mode.
      const glm::dmat3 R = scene.orientation_of(to);
      const glm::dvec3 n_xyz = to_crystal->principal_indices(lambda);
      Branch m[2];
      bool ok[2];
      double n_max = 0.0;
      for (int k = 0; k < 2; ++k) {
        const Mode md = refract_mode(R, n_xyz, k, d, N_f, cos_i, b.n);
        ok[k] = md.ok;
        n_max = std::max(n_max, md.n);
        if (!md.ok) continue;
        const glm::dvec3 p_t = glm::cross(md.dir, s);
        const double cs = glm::dot(md.vib, s), cp = glm::dot(md.vib, p_t);
        const glm::dvec3 a_k = cs * s + cp * p_i;  // e_k carried back to the incident frame
        const double T = cs * cs * md.f.T_s() + cp * cp * md.f.T_p();
        const double tau = std::sqrt(std::max(0.0, T));
        m[k] = b;
        m[k].dir = md.dir;
        m[k].n = md.n;
        m[k].mode = md.vib;
        m[k].crystal_mode = true;
        m[k].medium = to;
        m[k].origin = offset(md.dir);
        double inc = 0.0;
        for (int j = 0; j < starts; ++j) {
          const cd bk = dot(a_k, b.E[j]);
          inc += std::norm(bk);
          m[k].E[j] = (tau * bk) * real_vec(md.vib);
        }
        const double tr = field_power(m[k]);
        count_event(counters, inc, (1.0 - T) * inc, tr, false);
      }
      if (!ok[0] && !ok[1]) {
        // Both modes evanescent: total reflection back into `from`, with the Fresnel phases of
        // the higher mode index (the modes' TIR phases differ by O(Δn); both are TIR there).
        count_event(counters, incident, incident, 0.0, true);
        reflect_tir(fresnel_amplitudes(cos_i, n_max / b.n));
        continue;
      }
      if (ok[0] && ok[1]) {
        if (branches < kMaxJonesLeaves && top < int(stack.size())) {
          ++branches;
          stack[top++] = m[1];
          b = m[0];
        } else {
          const int keep = field_power(m[0]) >= field_power(m[1]) ? 0 : 1;
          if (counters) counters->capped_power += field_power(m[1 - keep]);
          b = m[keep];
        }
      } else {
        b = ok[0] ? m[0] : m[1];
      }
    }
  }
  return out;
}

}  // namespace pmsim
