#include "core/specimen/jones_path.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/base/units.h"
#include "core/crystal/section_optics.h"
#include "core/optics/beer_lambert.h"
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
  glm::dvec3 surface{0.0};      // where the segment begins, on the surface (origin is nudged off it)
  int medium = kSpecimenAir;
  double n = 1.0;               // index of this wave (a crystal mode's n_k along dir)
  glm::dvec3 mode{0.0};         // crystal: the mode's vibration e_k; unused in isotropic media
  bool crystal_mode = false;
  CVec E[2];                    // fields per start vibration, without the bulk phase
  double phase_rad = 0.0;       // k0·Σ n·L (+ the exit term), unwrapped
  int events = 0;
  double crystal_um = 0.0;      // geometric path inside crystals
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

// Mode k (0 fast, 1 slow) refracted into a crystal (axes R) from a wave of index n_i along d:
// Snell with the direction-dependent index n_k(t), by fixed-point iteration (each step shrinks the
// error by ~Δn·tanθt: a few steps reach double precision except near grazing refraction, where
// the last iterate is kept). The vibration is that of the section ⟂ the final direction, so it is
// exactly transverse to it.
Mode refract_mode(const glm::dmat3& R, const glm::dvec3& n_xyz, int k, const glm::dvec3& d, const glm::dvec3& N_f,
                  double cos_i, double n_i) {
  Mode m;
  glm::dvec3 t = d;
  double n_prev = 0.0;
  for (int it = 0; it < 12; ++it) {
    const SectionOptics so = section_optics(R, n_xyz, t);
    m.n = k == 0 ? so.n_fast : so.n_slow;
    if (std::abs(m.n - n_prev) < 1e-15) break;
    n_prev = m.n;
    const double eta = m.n / n_i;
    const double ct2 = snell_cos_t2(cos_i, eta);
    if (ct2 < 0.0) return m;  // evanescent (m.n: the index it would have)
    t = refract_dir(d, N_f, cos_i, std::sqrt(ct2), eta);
  }
  m.f = fresnel_amplitudes(cos_i, m.n / n_i);
  if (m.f.tir) return m;
  m.dir = refract_dir(d, N_f, cos_i, m.f.cos_t, m.f.eta);
  const SectionOptics so = section_optics(R, n_xyz, m.dir);
  m.vib = k == 0 ? so.fast : so.slow;
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

// s and p0 of the aplanatic map for direction d (any pair at d = ±ẑ, where the map is the identity).
void aplanatic_axes(const glm::dvec3& d, glm::dvec3& s, glm::dvec3& p0, glm::dvec3& p) {
  const glm::dvec3 c(-d.y, d.x, 0.0);  // ẑ × d
  const double l = std::sqrt(c.x * c.x + c.y * c.y);
  s = l > 1e-12 ? c / l : glm::dvec3(1.0, 0.0, 0.0);
  p0 = glm::cross(s, glm::dvec3(0.0, 0.0, 1.0));
  p = glm::cross(s, d);
  if (d.z < 0.0) p = -p;  // a downward ray: the same map with the lens on the other side
}

}  // namespace

glm::dvec3 aplanatic_map(const glm::dvec3& v, const glm::dvec3& d) {
  glm::dvec3 s, p0, p;
  aplanatic_axes(d, s, p0, p);
  return glm::dot(v, s) * s + glm::dot(v, p0) * p;
}

JonesPath trace_specimen_jones(const SpecimenScene& scene, const JonesPathRequest& q, InterfaceCounters* counters) {
  JonesPath out;
  if (counters) ++counters->paths;
  const double lambda = q.wavelength_nm;
  const double k0 = 2.0 * kPi / (lambda * 1e-3);  // per µm
  const int starts = q.forward_jones || q.starts > 1 ? 2 : 1;

  Branch b0;
  b0.dir = glm::normalize(q.dir);
  b0.origin = q.origin;
  b0.surface = q.origin;
  b0.medium = kSpecimenAir;
  b0.n = scene.index(kSpecimenAir, lambda, b0.dir);
  glm::dvec3 a0 = q.start_vibration - glm::dot(q.start_vibration, b0.dir) * b0.dir;
  a0 = glm::length(a0) > 1e-12 ? glm::normalize(a0) : s_axis(b0.dir, glm::dvec3(0, 0, 1));
  b0.E[0] = real_vec(a0);
  b0.E[1] = real_vec(glm::cross(b0.dir, a0));
  if (q.forward_jones) {
    b0.E[0] = real_vec(aplanatic_map({1.0, 0.0, 0.0}, b0.dir));
    b0.E[1] = real_vec(aplanatic_map({0.0, 1.0, 0.0}, b0.dir));
  }
  // The lit branches, summed at the end with their mutual coherence.
  struct Lit {
    cd amp[2];
    glm::dvec3 dir;
  };
  std::array<Lit, kMaxJonesLeaves> lit;
  int n_lit = 0;
  double crystal_um = 0.0;
  std::array<cd, kMaxJonesLeaves> exit_amp{};  // forward, analyzer in: per exit
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
        if (q.forward) {
          const double sin_exit = std::sqrt(b.dir.x * b.dir.x + b.dir.y * b.dir.y);
          if (b.medium == kSpecimenAir && b.dir.z > 0.0 && sin_exit <= q.objective_sin_max &&
              out.n_exits < kMaxJonesLeaves) {
            ++out.lit;
            const int i = out.n_exits++;
            JonesExit& e = out.exits[std::size_t(i)];
            e.point = b.events > 0 ? b.surface : b.origin;
            e.dir = b.dir;
            if (q.forward_jones) {
              const double phase = b.phase_rad - k0 * b.n * glm::dot(b.dir, e.point - x_start);
              const cd ph = std::polar(1.0, phase);
              glm::dvec3 s, p0, p;
              aplanatic_axes(b.dir, s, p0, p);
              // Back into the collimated space: the s and p components keep their amplitudes.
              for (int k = 0; k < 2; ++k) {
                const cd fs = ph * dot(s, b.E[k]), fp = ph * dot(p, b.E[k]);
                e.jones[std::size_t(k)] = fs * s.x + fp * p0.x;
                e.jones[std::size_t(2 + k)] = fs * s.y + fp * p0.y;
              }
              e.power = 0.5 * (power(b.E[0]) + power(b.E[1]));
              crystal_um = std::max(crystal_um, b.crystal_um);
            } else if (q.forward_analyzer_in) {
              glm::dvec3 a = q.forward_analyzer - glm::dot(q.forward_analyzer, b.dir) * b.dir;
              const double al = glm::length(a);
              // The plane wave leaving along the branch: its phase at the exit point.
              const double phase = b.phase_rad - k0 * b.n * glm::dot(b.dir, e.point - x_start);
              exit_amp[std::size_t(i)] = al > 1e-12 ? std::polar(1.0, phase) * dot(a / al, b.E[0]) : cd(0.0);
              crystal_um = std::max(crystal_um, b.crystal_um);
            } else {
              e.power = power(b.E[0]);
            }
          }
          break;
        }
        const double sin_exit = std::sqrt(b.dir.x * b.dir.x + b.dir.y * b.dir.y);
        if (b.medium == kSpecimenAir && b.dir.z < 0.0 && sin_exit <= q.condenser_sin_max) {
          ++out.lit;
          glm::dvec3 p = q.polarizer - glm::dot(q.polarizer, b.dir) * b.dir;
          const double pl = glm::length(p);
          if (pl > 1e-12) {
            p /= pl;
            // The plane wave arriving along the branch: its phase at the exit point.
            const double phase = b.phase_rad - k0 * b.n * glm::dot(b.dir, b.surface - x_start);
            const cd e = std::polar(1.0, phase);
            if (n_lit < kMaxJonesLeaves) {
              Lit& l = lit[std::size_t(n_lit++)];
              for (int s = 0; s < starts; ++s) l.amp[s] = e * dot(p, b.E[s]);
              l.dir = b.dir;
              crystal_um = std::max(crystal_um, b.crystal_um);
            }
          }
        }
        break;
      }
      // Bulk: phase and pleochroic attenuation along the segment, measured from the surface it
      // began on (not from the nudged origin: 1e-3 µm per face is 4e-3 rad of calcite's phase).
      const double seg = glm::length(hit.point - b.surface);
      b.phase_rad += k0 * b.n * seg;
      if (b.crystal_mode) {
        b.crystal_um += seg;
        const Crystal* c = scene.crystal_of(b.medium);
        if (c && c->absorbing()) {
          const glm::dvec3 mu = c->principal_absorption_per_um(lambda);
          const glm::dmat3 R = scene.orientation_of(b.medium);
          const double ex = glm::dot(b.mode, R[0]), ey = glm::dot(b.mode, R[1]), ez = glm::dot(b.mode, R[2]);
          // 0 past the opaque cut-off (beer_lambert.h): ilmenite's e^-69 would be a subnormal float.
          const double att =
              amplitude_attenuation(0.5 * (mu.x * ex * ex + mu.y * ey * ey + mu.z * ez * ez) * seg);
          for (int s = 0; s < starts; ++s) b.E[s] = cd(att) * b.E[s];
        }
      } else if (const double mu = scene.isotropic_absorption_per_um(b.medium, lambda); mu > 0.0) {
        // An absorbing isotropic mineral (magnetite) is no crystal to the tracer, but absorbs all
        // the same: Beer–Lambert along the segment, 0 past the opaque cut-off.
        const double att = amplitude_attenuation(0.5 * mu * seg);
        for (int s = 0; s < starts; ++s) b.E[s] = cd(att) * b.E[s];
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
      // Both modes go on: the second waits on the stack, or, past the cap on leaves, the weaker is
      // dropped and its power counted.
      const auto follow_both = [&](Branch(&m)[2]) {
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
      const auto offset = [&](const glm::dvec3& dir) {
        b.surface = hit.point;
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
        follow_both(m);
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
      Mode md[2];
      for (int k = 0; k < 2; ++k) {
        md[k] = refract_mode(R, n_xyz, k, d, N_f, cos_i, b.n);
        ok[k] = md[k].ok;
        n_max = std::max(n_max, md[k].n);
      }
      // Each mode's vibration carried back to the incident frame, a_k = (e_k·s)s + (e_k·p_t,k)p_i
      // (unit: e_k ⟂ t_k). When the modes refract to different directions the two a_k are not
      // quite orthogonal; the symmetric (Löwdin) orthonormalization S^(−1/2), the orthogonal pair
      // nearest to them, makes the modes share the incident power exactly.
      glm::dvec2 img[2];
      for (int k = 0; k < 2; ++k)
        if (ok[k]) {
          const glm::dvec3 p_t = glm::cross(md[k].dir, s);
          img[k] = glm::normalize(glm::dvec2(glm::dot(md[k].vib, s), glm::dot(md[k].vib, p_t)));
        }
      if (ok[0] && ok[1]) {
        const double c = std::clamp(glm::dot(img[0], img[1]), -0.999999, 0.999999);
        const double u = 1.0 / std::sqrt(1.0 + c), v = 1.0 / std::sqrt(1.0 - c);
        const double al = 0.5 * (u + v), be = 0.5 * (u - v);
        const glm::dvec2 o0 = al * img[0] + be * img[1], o1 = be * img[0] + al * img[1];
        img[0] = o0;
        img[1] = o1;
      }
      for (int k = 0; k < 2; ++k) {
        if (!ok[k]) continue;
        const double cs = img[k].x, cp = img[k].y;
        const glm::dvec3 a_k = cs * s + cp * p_i;
        const double T = cs * cs * md[k].f.T_s() + cp * cp * md[k].f.T_p();
        const double tau = std::sqrt(std::max(0.0, T));
        m[k] = b;
        m[k].dir = md[k].dir;
        m[k].n = md[k].n;
        m[k].mode = md[k].vib;
        m[k].crystal_mode = true;
        m[k].medium = to;
        m[k].origin = offset(md[k].dir);
        m[k].surface = hit.point;
        double inc = 0.0;
        for (int j = 0; j < starts; ++j) {
          const cd bk = dot(a_k, b.E[j]);
          inc += std::norm(bk);
          m[k].E[j] = (tau * bk) * real_vec(md[k].vib);
        }
        count_event(counters, inc, (1.0 - T) * inc, field_power(m[k]), false);
      }
      if (!ok[0] && !ok[1]) {
        // Both modes evanescent: total reflection back into `from`, with the Fresnel phases of
        // the higher mode index (the modes' TIR phases differ by O(Δn); both are TIR there).
        count_event(counters, incident, incident, 0.0, true);
        reflect_tir(fresnel_amplitudes(cos_i, n_max / b.n));
        continue;
      }
      if (ok[0] && ok[1]) {
        follow_both(m);
      } else {
        b = ok[0] ? m[0] : m[1];
      }
    }
  }
  // Branches leaving in one direction come from one point of the condenser's (spatially
  // incoherent) source and interfere: a plate's two waves. Branches leaving in different directions
  // stand for different source points; their backward pairing is a stand-in for the true coherent
  // partner (the ray from a nearby pupil point that leaves along the same direction), whose phase
  // differs from this branch's by about k0·Δx·Δθ, with the branches' lateral separation Δx ≈ L·Δθ
  // for a crystal path L. So the pair's coherence is γ = exp(−k0·L·|Δd|²): 1 for parallel faces,
  // fringes kept at a wedge of small Δθ, incoherent (intensities added) for branches that leave by
  // other faces. A Gaussian kernel of the directions: the sum stays a positive form.
  for (int i = 0; i < n_lit; ++i)
    for (int k = 0; k < starts; ++k) out.power[k] += std::norm(lit[std::size_t(i)].amp[k]);
  for (int i = 0; i < n_lit; ++i)
    for (int j = i + 1; j < n_lit; ++j) {
      const Lit& li = lit[std::size_t(i)];
      const Lit& lj = lit[std::size_t(j)];
      const glm::dvec3 dd = li.dir - lj.dir;
      const double gamma = std::exp(-k0 * crystal_um * glm::dot(dd, dd));
      if (gamma < 1e-12) continue;
      for (int k = 0; k < starts; ++k) out.power[k] += 2.0 * gamma * std::real(li.amp[k] * std::conj(lj.amp[k]));
    }
  for (int k = 0; k < starts; ++k) out.power[k] = std::max(0.0, out.power[k]);
  out.k0_crystal_um = k0 * crystal_um;
  if (q.forward && !q.forward_jones) {
    // Forward: each exit's share of the coherent sum (see JonesPathRequest::forward_analyzer_in).
    out.power[0] = 0.0;
    for (int i = 0; i < out.n_exits; ++i) {
      JonesExit& ei = out.exits[std::size_t(i)];
      if (q.forward_analyzer_in) {
        const cd ai = exit_amp[std::size_t(i)];
        ei.power = std::norm(ai);
        for (int j = 0; j < out.n_exits; ++j) {
          if (j == i) continue;
          const glm::dvec3 dd = ei.dir - out.exits[std::size_t(j)].dir;
          const double gamma = std::exp(-k0 * crystal_um * glm::dot(dd, dd));
          if (gamma >= 1e-12) ei.power += gamma * std::real(ai * std::conj(exit_amp[std::size_t(j)]));
        }
      }
      out.power[0] += ei.power;
    }
    out.power[0] = std::max(0.0, out.power[0]);
  }
  return out;
}

}  // namespace pmsim
