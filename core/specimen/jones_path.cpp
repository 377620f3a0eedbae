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

namespace {

// A path is traced in two phases that share its request and the constants of its wavelength:
// propagation (Propagator) follows the branch tree through the specimen's interfaces, and every
// branch that leaves the specimen goes to scoring (Scorer), which keeps what reaches the
// condenser (backward) or the objective (forward) and sums it coherently at the end.
struct PathSetup {
  const SpecimenScene& scene;
  const JonesPathRequest& q;
  InterfaceCounters* counters;
  double lambda;
  double k0;   // per µm
  int starts;  // start vibrations carried: 1, or 2 (analyzer out, forward_jones)
  glm::dvec3 x_start;

  double field_power(const Branch& b) const { return power(b.E[0]) + (starts > 1 ? power(b.E[1]) : 0.0); }
};

PathSetup path_setup(const SpecimenScene& scene, const JonesPathRequest& q, InterfaceCounters* counters) {
  const double lambda = q.wavelength_nm;
  const double k0 = 2.0 * kPi / (lambda * 1e-3);  // per µm
  const int starts = q.forward_jones || q.starts > 1 ? 2 : 1;
  return {scene, q, counters, lambda, k0, starts, q.origin};
}

// The path's first branch, in the air where the path starts, with the start vibrations.
Branch first_branch(const PathSetup& p) {
  const JonesPathRequest& q = p.q;
  Branch b0;
  b0.dir = glm::normalize(q.dir);
  b0.origin = q.origin;
  b0.surface = q.origin;
  b0.medium = kSpecimenAir;
  b0.n = p.scene.index(kSpecimenAir, p.lambda, b0.dir);
  glm::dvec3 a0 = q.start_vibration - glm::dot(q.start_vibration, b0.dir) * b0.dir;
  a0 = glm::length(a0) > 1e-12 ? glm::normalize(a0) : s_axis(b0.dir, glm::dvec3(0, 0, 1));
  b0.E[0] = real_vec(a0);
  b0.E[1] = real_vec(glm::cross(b0.dir, a0));
  if (q.forward_jones) {
    b0.E[0] = real_vec(aplanatic_map({1.0, 0.0, 0.0}, b0.dir));
    b0.E[1] = real_vec(aplanatic_map({0.0, 1.0, 0.0}, b0.dir));
  }
  return b0;
}

// ---- Scoring: the branches that leave the specimen, and their coherent sum ----

class Scorer {
 public:
  explicit Scorer(const PathSetup& p) : p_(p) {}
  // A branch that meets no further interface.
  void leave(const Branch& b, JonesPath& out) {
    ++out.leaves;
    if (p_.q.forward)
      forward_exit(b, out);
    else
      backward_exit(b, out);
  }
  void finish(JonesPath& out) const {
    sum_lit(out);
    out.k0_crystal_um = p_.k0 * crystal_um_;
    if (p_.q.forward && !p_.q.forward_jones) share_exits(out);
  }

 private:
  void forward_exit(const Branch& b, JonesPath& out);
  void backward_exit(const Branch& b, JonesPath& out);
  void sum_lit(JonesPath& out) const;
  void share_exits(JonesPath& out) const;

  const PathSetup& p_;
  // The lit branches, summed at the end with their mutual coherence.
  struct Lit {
    cd amp[2];
    glm::dvec3 dir;
  };
  std::array<Lit, kMaxJonesLeaves> lit_;
  int n_lit_ = 0;
  double crystal_um_ = 0.0;
  std::array<cd, kMaxJonesLeaves> exit_amp_{};  // forward, analyzer in: per exit
};

// Forward: a branch leaving the cover glass upward inside the objective's cone is an exit.
void Scorer::forward_exit(const Branch& b, JonesPath& out) {
  const JonesPathRequest& q = p_.q;
  const double k0 = p_.k0;
  const double sin_exit = std::sqrt(b.dir.x * b.dir.x + b.dir.y * b.dir.y);
  if (b.medium == kSpecimenAir && b.dir.z > 0.0 && sin_exit <= q.objective_sin_max &&
      out.n_exits < kMaxJonesLeaves) {
    ++out.lit;
    const int i = out.n_exits++;
    JonesExit& e = out.exits[std::size_t(i)];
    e.point = b.events > 0 ? b.surface : b.origin;
    e.dir = b.dir;
    if (q.forward_jones) {
      const double phase = b.phase_rad - k0 * b.n * glm::dot(b.dir, e.point - p_.x_start);
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
      crystal_um_ = std::max(crystal_um_, b.crystal_um);
    } else if (q.forward_analyzer_in) {
      glm::dvec3 a = q.forward_analyzer - glm::dot(q.forward_analyzer, b.dir) * b.dir;
      const double al = glm::length(a);
      // The plane wave leaving along the branch: its phase at the exit point.
      const double phase = b.phase_rad - k0 * b.n * glm::dot(b.dir, e.point - p_.x_start);
      exit_amp_[std::size_t(i)] = al > 1e-12 ? std::polar(1.0, phase) * dot(a / al, b.E[0]) : cd(0.0);
      crystal_um_ = std::max(crystal_um_, b.crystal_um);
    } else {
      e.power = power(b.E[0]);
    }
  }
}

// Backward: a branch leaving below the slide inside the condenser's cone is lit, projected on
// the polarizer.
void Scorer::backward_exit(const Branch& b, JonesPath& out) {
  const JonesPathRequest& q = p_.q;
  const double sin_exit = std::sqrt(b.dir.x * b.dir.x + b.dir.y * b.dir.y);
  if (b.medium == kSpecimenAir && b.dir.z < 0.0 && sin_exit <= q.condenser_sin_max) {
    ++out.lit;
    glm::dvec3 p = q.polarizer - glm::dot(q.polarizer, b.dir) * b.dir;
    const double pl = glm::length(p);
    if (pl > 1e-12) {
      p /= pl;
      // The plane wave arriving along the branch: its phase at the exit point.
      const double phase = b.phase_rad - p_.k0 * b.n * glm::dot(b.dir, b.surface - p_.x_start);
      const cd e = std::polar(1.0, phase);
      if (n_lit_ < kMaxJonesLeaves) {
        Lit& l = lit_[std::size_t(n_lit_++)];
        for (int s = 0; s < p_.starts; ++s) l.amp[s] = e * dot(p, b.E[s]);
        l.dir = b.dir;
        crystal_um_ = std::max(crystal_um_, b.crystal_um);
      }
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
void Scorer::sum_lit(JonesPath& out) const {
  const int starts = p_.starts;
  const double k0 = p_.k0;
  for (int i = 0; i < n_lit_; ++i)
    for (int k = 0; k < starts; ++k) out.power[k] += std::norm(lit_[std::size_t(i)].amp[k]);
  for (int i = 0; i < n_lit_; ++i)
    for (int j = i + 1; j < n_lit_; ++j) {
      const Lit& li = lit_[std::size_t(i)];
      const Lit& lj = lit_[std::size_t(j)];
      const glm::dvec3 dd = li.dir - lj.dir;
      const double gamma = std::exp(-k0 * crystal_um_ * glm::dot(dd, dd));
      if (gamma < 1e-12) continue;
      for (int k = 0; k < starts; ++k) out.power[k] += 2.0 * gamma * std::real(li.amp[k] * std::conj(lj.amp[k]));
    }
  for (int k = 0; k < starts; ++k) out.power[k] = std::max(0.0, out.power[k]);
}

// Forward: each exit's share of the coherent sum (see JonesPathRequest::forward_analyzer_in).
void Scorer::share_exits(JonesPath& out) const {
  const double k0 = p_.k0;
  out.power[0] = 0.0;
  for (int i = 0; i < out.n_exits; ++i) {
    JonesExit& ei = out.exits[std::size_t(i)];
    if (p_.q.forward_analyzer_in) {
      const cd ai = exit_amp_[std::size_t(i)];
      ei.power = std::norm(ai);
      for (int j = 0; j < out.n_exits; ++j) {
        if (j == i) continue;
        const glm::dvec3 dd = ei.dir - out.exits[std::size_t(j)].dir;
        const double gamma = std::exp(-k0 * crystal_um_ * glm::dot(dd, dd));
        if (gamma >= 1e-12) ei.power += gamma * std::real(ai * std::conj(exit_amp_[std::size_t(j)]));
      }
    }
    out.power[0] += ei.power;
  }
  out.power[0] = std::max(0.0, out.power[0]);
}

// ---- Propagation: the branch tree through the specimen's interfaces ----

// An interface a branch meets: its sides, the incident frame (s, p_i; fresnel.h's s/p frame)
// and the incident field's components in it.
struct Interface {
  SpecimenHit hit;
  int from = kSpecimenAir, to = kSpecimenAir;
  glm::dvec3 N_f{0.0};  // faces the incident ray
  double cos_i = 1.0;
  glm::dvec3 d{0.0}, s{0.0}, p_i{0.0};
  cd Es[2], Ep[2];
  double incident = 0.0;  // the field's power
  const Crystal* from_crystal = nullptr;
  const Crystal* to_crystal = nullptr;
};

// The start of a segment leaving the surface along dir: nudged off it to the side dir goes
// (the branch's `surface` is set to the hit point).
glm::dvec3 offset(Branch& b, const SpecimenHit& hit, const glm::dvec3& dir) {
  b.surface = hit.point;
  return hit.point + (glm::dot(dir, hit.normal) > 0.0 ? 1e-3 : -1e-3) * hit.normal;
}

class Propagator {
 public:
  Propagator(const PathSetup& p, Scorer& scorer, JonesPath& out) : p_(p), scorer_(scorer), out_(out) {}
  void run(const Branch& b0) {
    stack_[top_++] = b0;
    while (top_ > 0) follow(stack_[--top_]);
  }

 private:
  void follow(Branch b);
  void absorb(Branch& b, double seg) const;
  Interface interface_of(const Branch& b, const SpecimenHit& hit) const;
  void into_isotropic(Branch& b, const Interface& at);
  void into_crystal(Branch& b, const Interface& at);
  void reflect_tir(Branch& b, const Interface& at, const FresnelAmplitudes& f);
  void follow_both(Branch& b, Branch (&m)[2]);

  const PathSetup& p_;
  Scorer& scorer_;
  JonesPath& out_;
  std::array<Branch, 2 * kMaxJonesLeaves> stack_;
  int top_ = 0;
  int branches_ = 1;  // leaves of the tree so far (live + ended)
};

// One branch, interface after interface, until it leaves the specimen (scored) or is lost; the
// other modes of its splits wait on the stack.
void Propagator::follow(Branch b) {
  SpecimenHit hit;
  for (;;) {
    if (b.events >= p_.q.max_interfaces) {
      if (p_.counters) ++p_.counters->lost;
      ++out_.leaves;
      return;
    }
    if (!p_.scene.intersect(b.origin, b.dir, 0.0, hit)) {
      scorer_.leave(b, out_);
      return;
    }
    // Bulk: phase and pleochroic attenuation along the segment, measured from the surface it
    // began on (not from the nudged origin: 1e-3 µm per face is 4e-3 rad of calcite's phase).
    const double seg = glm::length(hit.point - b.surface);
    b.phase_rad += p_.k0 * b.n * seg;
    absorb(b, seg);
    ++b.events;
    ++out_.interfaces;
    const Interface at = interface_of(b, hit);
    if (!at.to_crystal)
      into_isotropic(b, at);
    else
      into_crystal(b, at);
  }
}

void Propagator::absorb(Branch& b, double seg) const {
  const int starts = p_.starts;
  if (b.crystal_mode) {
    b.crystal_um += seg;
    const Crystal* c = p_.scene.crystal_of(b.medium);
    if (c && c->absorbing()) {
      const glm::dvec3 mu = c->principal_absorption_per_um(p_.lambda);
      const glm::dmat3 R = p_.scene.orientation_of(b.medium);
      const double ex = glm::dot(b.mode, R[0]), ey = glm::dot(b.mode, R[1]), ez = glm::dot(b.mode, R[2]);
      // 0 past the opaque cut-off (beer_lambert.h): ilmenite's e^-69 would be a subnormal float.
      const double att =
          amplitude_attenuation(0.5 * (mu.x * ex * ex + mu.y * ey * ey + mu.z * ez * ez) * seg);
      for (int s = 0; s < starts; ++s) b.E[s] = cd(att) * b.E[s];
    }
  } else if (const double mu = p_.scene.isotropic_absorption_per_um(b.medium, p_.lambda); mu > 0.0) {
    // An absorbing isotropic mineral (magnetite) is no crystal to the tracer, but absorbs all
    // the same: Beer–Lambert along the segment, 0 past the opaque cut-off.
    const double att = amplitude_attenuation(0.5 * mu * seg);
    for (int s = 0; s < starts; ++s) b.E[s] = cd(att) * b.E[s];
  }
}

Interface Propagator::interface_of(const Branch& b, const SpecimenHit& hit) const {
  Interface at;
  at.hit = hit;
  const bool from_front = glm::dot(b.dir, hit.normal) < 0.0;
  at.from = from_front ? hit.front : hit.back;
  at.to = from_front ? hit.back : hit.front;
  at.N_f = from_front ? hit.normal : -hit.normal;  // faces the incident ray
  at.cos_i = std::min(1.0, std::abs(glm::dot(b.dir, hit.normal)));
  at.d = b.dir;
  at.s = s_axis(at.d, hit.normal);
  at.p_i = glm::cross(at.d, at.s);
  for (int k = 0; k < p_.starts; ++k) {
    at.Es[k] = dot(at.s, b.E[k]);
    at.Ep[k] = dot(at.p_i, b.E[k]);
  }
  at.incident = p_.field_power(b);
  at.to_crystal = p_.scene.crystal_of(at.to);
  at.from_crystal = p_.scene.crystal_of(at.from);
  return at;
}

// Both modes go on: the second waits on the stack, or, past the cap on leaves, the weaker is
// dropped and its power counted.
void Propagator::follow_both(Branch& b, Branch (&m)[2]) {
  if (branches_ < kMaxJonesLeaves && top_ < int(stack_.size())) {
    ++branches_;
    stack_[top_++] = m[1];
    b = m[0];
  } else {
    const int keep = p_.field_power(m[0]) >= p_.field_power(m[1]) ? 0 : 1;
    if (p_.counters) p_.counters->capped_power += p_.field_power(m[1 - keep]);
    b = m[keep];
  }
}

// Reflection under TIR: mirror direction, r_s, r_p with their phases; inside a crystal the
// reflected field is split again into its modes.
void Propagator::reflect_tir(Branch& b, const Interface& at, const FresnelAmplitudes& f) {
  const int starts = p_.starts;
  const glm::dvec3& s = at.s;
  const glm::dvec3 r = reflect_dir(at.d, at.hit.normal);
  const glm::dvec3 p_r = glm::cross(s, r);
  for (int k = 0; k < starts; ++k) b.E[k] = (f.r_s * at.Es[k]) * real_vec(s) + (f.r_p * at.Ep[k]) * real_vec(p_r);
  b.dir = r;
  b.origin = offset(b, at.hit, r);
  b.medium = at.from;
  if (!at.from_crystal) return;
  const glm::dmat3 R = p_.scene.orientation_of(at.from);
  const glm::dvec3 n_xyz = at.from_crystal->principal_indices(p_.lambda);
  const SectionOptics so = section_optics(R, n_xyz, r);
  Branch m[2] = {b, b};
  for (int k = 0; k < 2; ++k) {
    m[k].mode = k == 0 ? so.fast : so.slow;
    m[k].n = k == 0 ? so.n_fast : so.n_slow;
    m[k].crystal_mode = true;
    for (int j = 0; j < starts; ++j) m[k].E[j] = dot(m[k].mode, b.E[j]) * real_vec(m[k].mode);
  }
  follow_both(b, m);
}

// Into an isotropic medium (or a crystal mode out into one): the power-normalized Fresnel
// amplitudes in the s/p frame, or TIR.
void Propagator::into_isotropic(Branch& b, const Interface& at) {
  const int starts = p_.starts;
  const glm::dvec3& d = at.d;
  const glm::dvec3& s = at.s;
  const double n_t = p_.scene.index(at.to, p_.lambda, d);
  const FresnelAmplitudes f = fresnel_amplitudes(at.cos_i, n_t / b.n);
  if (f.tir) {
    count_event(p_.counters, at.incident, at.incident, 0.0, true);
    reflect_tir(b, at, f);
    return;
  }
  const double g = std::sqrt(f.power_factor());
  const glm::dvec3 t = refract_dir(d, at.N_f, at.cos_i, f.cos_t, f.eta);
  const glm::dvec3 p_t = glm::cross(t, s);
  double reflected = 0.0;
  for (int k = 0; k < starts; ++k) {
    reflected += f.R_s() * std::norm(at.Es[k]) + f.R_p() * std::norm(at.Ep[k]);
    b.E[k] = (g * f.t_s * at.Es[k]) * real_vec(s) + (g * f.t_p * at.Ep[k]) * real_vec(p_t);
  }
  count_event(p_.counters, at.incident, reflected, p_.field_power(b), false);
  b.dir = t;
  b.n = n_t;
  b.medium = at.to;
  b.crystal_mode = false;
  b.origin = offset(b, at.hit, t);
}

// The symmetric (Löwdin) orthonormalization S^(−1/2) of two unit 2-vectors: the orthogonal pair
// nearest to them.
void lowdin_orthonormalize(glm::dvec2 (&img)[2]) {
  const double c = std::clamp(glm::dot(img[0], img[1]), -0.999999, 0.999999);
  const double u = 1.0 / std::sqrt(1.0 + c), v = 1.0 / std::sqrt(1.0 - c);
  const double al = 0.5 * (u + v), be = 0.5 * (u - v);
  const glm::dvec2 o0 = al * img[0] + be * img[1], o1 = be * img[0] + al * img[1];
  img[0] = o0;
  img[1] = o1;
}

// Into a crystal: one branch per mode.
void Propagator::into_crystal(Branch& b, const Interface& at) {
  const int starts = p_.starts;
  const glm::dvec3& s = at.s;
  const glm::dmat3 R = p_.scene.orientation_of(at.to);
  const glm::dvec3 n_xyz = at.to_crystal->principal_indices(p_.lambda);
  Branch m[2];
  bool ok[2];
  double n_max = 0.0;
  Mode md[2];
  for (int k = 0; k < 2; ++k) {
    md[k] = refract_mode(R, n_xyz, k, at.d, at.N_f, at.cos_i, b.n);
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
  if (ok[0] && ok[1]) lowdin_orthonormalize(img);
  for (int k = 0; k < 2; ++k) {
    if (!ok[k]) continue;
    const double cs = img[k].x, cp = img[k].y;
    const glm::dvec3 a_k = cs * s + cp * at.p_i;
    const double T = cs * cs * md[k].f.T_s() + cp * cp * md[k].f.T_p();
    const double tau = std::sqrt(std::max(0.0, T));
    m[k] = b;
    m[k].dir = md[k].dir;
    m[k].n = md[k].n;
    m[k].mode = md[k].vib;
    m[k].crystal_mode = true;
    m[k].medium = at.to;
    m[k].origin = offset(b, at.hit, md[k].dir);
    m[k].surface = at.hit.point;
    double inc = 0.0;
    for (int j = 0; j < starts; ++j) {
      const cd bk = dot(a_k, b.E[j]);
      inc += std::norm(bk);
      m[k].E[j] = (tau * bk) * real_vec(md[k].vib);
    }
    count_event(p_.counters, inc, (1.0 - T) * inc, p_.field_power(m[k]), false);
  }
  if (!ok[0] && !ok[1]) {
    // Both modes evanescent: total reflection back into `from`, with the Fresnel phases of
    // the higher mode index (the modes' TIR phases differ by O(Δn); both are TIR there).
    count_event(p_.counters, at.incident, at.incident, 0.0, true);
    reflect_tir(b, at, fresnel_amplitudes(at.cos_i, n_max / b.n));
    return;
  }
  if (ok[0] && ok[1]) {
    follow_both(b, m);
  } else {
    b = ok[0] ? m[0] : m[1];
  }
}

}  // namespace

JonesPath trace_specimen_jones(const SpecimenScene& scene, const JonesPathRequest& q, InterfaceCounters* counters) {
  JonesPath out;
  if (counters) ++counters->paths;
  const PathSetup p = path_setup(scene, q, counters);
  Scorer scorer(p);
  Propagator(p, scorer, out).run(first_branch(p));
  scorer.finish(out);
  return out;
}

}  // namespace pmsim
