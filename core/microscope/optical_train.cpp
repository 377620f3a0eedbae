#include "core/microscope/optical_train.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "core/base/conventions.h"
#include "core/base/units.h"

namespace pmsim {

TrainState make_train(const Scene& scene, const CompensatorPlate& comp, double wavelength_nm) {
  TrainState t;
  t.wavelength_nm = wavelength_nm;
  t.polarizer = polarizer_direction(scene.polarizer_deg);
  if (scene.analyzer_in) {
    t.outputs = 1;
    t.output[0] = polarizer_direction(scene.analyzer_deg);
  } else {
    t.outputs = 2;
    t.output[0] = glm::dvec2(kLabEast);
    t.output[1] = glm::dvec2(kLabNorth);
  }
  if (comp.present) {
    t.comp_modes = 2;
    t.comp_dir[0] = glm::dvec2(kSlotFast);
    t.comp_dir[1] = glm::dvec2(kSlotSlow);
    const double g = compensator_retardation_nm(comp, wavelength_nm);
    const double h = 0.5;
    const double gp = compensator_retardation_nm(comp, wavelength_nm + h);
    const double gm = compensator_retardation_nm(comp, wavelength_nm - h);
    const double two_pi = 2.0 * kPi;
    t.chi_rad = two_pi * g / wavelength_nm;
    // d(2πΓ/λ)/dλ = 2π(Γ'/λ − Γ/λ²)
    t.dchi_dnm = two_pi * ((gp - gm) / (2 * h) / wavelength_nm - g / (wavelength_nm * wavelength_nm));
    t.comp_jones = plate_jones(comp.spec, kLightDirection, wavelength_nm);
  }
  return t;
}

TrainState train_in_specimen_frame(const TrainState& lab, double stage_rad) {
  const double c = std::cos(stage_rad), s = std::sin(stage_rad);
  const auto turn = [&](const glm::dvec2& v) { return glm::dvec2(c * v.x + s * v.y, -s * v.x + c * v.y); };  // R(−θ)·v
  TrainState t = lab;
  t.polarizer = turn(lab.polarizer);
  for (int o = 0; o < 2; ++o) t.output[o] = turn(lab.output[o]);
  for (int m = 0; m < 2; ++m) t.comp_dir[m] = turn(lab.comp_dir[m]);
  t.comp_jones = rotation(-stage_rad) * lab.comp_jones * rotation(stage_rad);
  return t;
}

JonesVector jones_output(const TrainState& t, const JonesMatrix& sample, int o) {
  const JonesVector in{t.polarizer.x, t.polarizer.y};
  const JonesVector e = t.comp_jones * (sample * in);
  return JonesVector{e.x * t.output[o].x + e.y * t.output[o].y, 0.0};
}

double jones_transmission(const TrainState& t, const JonesMatrix& sample) {
  double s = 0.0;
  for (int o = 0; o < t.outputs; ++o) s += jones_output(t, sample, o).intensity();
  return s;
}

namespace {
inline double sinc(double x) { return std::fabs(x) < 1e-8 ? 1.0 : std::sin(x) / x; }
}  // namespace

double modal_transmission(const TrainState& t, const ModalPoint& m, double band_nm) {
  // Dual basis of the (possibly slightly non-orthogonal) mode directions: a field f splits into
  // Σ (ẽ_m·f) e_m.
  glm::dvec2 e1 = m.e1, e2 = m.e2;
  double det = e1.x * e2.y - e1.y * e2.x;
  if (std::fabs(det) < 1e-9) {  // degenerate pair: complete with the orthogonal direction
    e2 = {-e1.y, e1.x};
    det = 1.0;
  }
  const glm::dvec2 d1{e2.y / det, -e2.x / det}, d2{-e1.y / det, e1.x / det};
  const double a1 = m.t1 * glm::dot(d1, t.polarizer), a2 = m.t2 * glm::dot(d2, t.polarizer);
  const double lambda = t.wavelength_nm;
  const double two_pi = 2.0 * kPi;
  const double phi = two_pi * m.gamma_nm / lambda;
  const double dphi = two_pi * (m.dgamma_dnm / lambda - m.gamma_nm / (lambda * lambda));
  // Terms (mode m, compensator mode k) with phase (s_m·φ + s_k·χ)/2, s = −1 fast, +1 slow.
  double amp[4], ph[4], dph[4];
  int n = 0;
  double total = 0.0;
  for (int o = 0; o < t.outputs; ++o) {
    n = 0;
    for (int mi = 0; mi < 2; ++mi) {
      const glm::dvec2& em = mi == 0 ? e1 : e2;
      const double am = mi == 0 ? a1 : a2;
      const double sm = mi == 0 ? -0.5 : 0.5;
      for (int k = 0; k < t.comp_modes; ++k) {
        double g;
        double sk = 0.0;
        if (t.comp_modes == 1) {
          g = glm::dot(t.output[o], em);
        } else {
          g = glm::dot(t.output[o], t.comp_dir[k]) * glm::dot(t.comp_dir[k], em);
          sk = k == 0 ? -0.5 : 0.5;
        }
        amp[n] = g * am;
        ph[n] = sm * phi + sk * t.chi_rad;
        dph[n] = sm * dphi + sk * t.dchi_dnm;
        ++n;
      }
    }
    for (int i = 0; i < n; ++i) {
      total += amp[i] * amp[i];
      for (int j = i + 1; j < n; ++j) {
        if (amp[i] == 0.0 || amp[j] == 0.0) continue;
        total += 2.0 * amp[i] * amp[j] * std::cos(ph[i] - ph[j]) * sinc(0.5 * (dph[i] - dph[j]) * band_nm);
      }
    }
  }
  return total;
}

}  // namespace pmsim
