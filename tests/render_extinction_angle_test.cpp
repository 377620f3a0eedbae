// Extinction angles measured on rendered images of plates cut along crystal planes (sample.cut),
// compared with the angle the section optics computes from the mineral data and with the ranges
// Deer, Howie & Zussman (2013, "DHZ") and Nesse (2012) publish. The renderer knows nothing of
// cleavages or extinction angles: it only gets the indicatrix turned into the lab frame by the cut.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/crystal/lattice.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/crystal/section_optics.h"
#include "core/render/progressive_renderer.h"

using namespace pmsim;

namespace {

constexpr double kDeg = 180.0 / kPi;
constexpr double kWavelength_nm = 550.0;

struct Cut {
  const char* mineral;
  const char* plane;
  const char* north;
};

SectionOptics optics_of(const Cut& c) {
  const MineralCrystallography& m = *find_mineral_crystallography(c.mineral);
  return section_optics(m.indicatrix_axes, find_mineral(c.mineral).principal_indices(kWavelength_nm),
                        plane_normal(m.cell, parse_miller_plane(c.plane)));
}

// A small plate between crossed polars (polarizer E–W, analyzer N–S) in monochromatic light, its
// thickness making the section a half-wave plate (Γ = λ/2: the brightest 45° position, so the
// fit below is well conditioned for every mineral).
Scene plate_scene(const Cut& c, double stage_deg) {
  Scene s;
  s.sample.type = SampleType::Plate;
  s.sample.mineral = c.mineral;
  s.sample.cut = SampleCut{c.plane, c.north};
  const SectionOptics o = optics_of(c);
  s.sample.thickness_um = 0.5 * kWavelength_nm / (1000.0 * (o.n_slow - o.n_fast));
  s.polarizer_deg = 0;
  s.analyzer_deg = 90;
  s.analyzer_in = true;
  s.stage_deg = stage_deg;
  s.render.width = s.render.height = 4;
  s.render.spp = 1;
  s.render.single_wavelength_nm = kWavelength_nm;
  return s;
}

double brightness(const Scene& s) {
  const RenderImage img = ProgressiveRenderer::render(s, 1);
  double y = 0;
  for (std::size_t i = 1; i < img.xyz.size(); i += 3) y += img.xyz[i];
  return y / (img.xyz.size() / 3);
}

struct Measured {
  double stage_deg;  // stage angle of extinction in [0, 90)
  double contrast;   // (max − min)/max of the fitted curve: 1 for a clean extinction
};

// Between crossed polars I(θ) = I0·sin²(2(θ − θ0))·sin²(πΓ/λ) = A − B·cos(4(θ − θ0)) (Nesse 2012
// ch. 7). Stage steps of 5° over 180° sample it evenly, so the Fourier coefficients of cos 4θ and
// sin 4θ give θ0 directly (least squares on an orthogonal basis); a parabola through renders at
// θ0 − 1°, θ0, θ0 + 1° then refines it on the images themselves.
Measured measure_extinction(const Cut& c) {
  const int n = 36;
  double s0 = 0, sc = 0, ss = 0;
  for (int i = 0; i < n; ++i) {
    const double t = i * 5.0;
    const double I = brightness(plate_scene(c, t));
    s0 += I / n;
    sc += 2.0 * I * std::cos(4 * t / kDeg) / n;
    ss += 2.0 * I * std::sin(4 * t / kDeg) / n;
  }
  const double amp = std::hypot(sc, ss);
  double t0 = (std::atan2(ss, sc) * kDeg + 180.0) / 4.0;  // minimum of A + amp·cos(4θ − ψ)
  const double h = 1.0;
  const double im = brightness(plate_scene(c, t0 - h)), i0 = brightness(plate_scene(c, t0)),
               ip = brightness(plate_scene(c, t0 + h));
  const double curv = im - 2 * i0 + ip;
  if (curv > 0) t0 += 0.5 * h * (im - ip) / curv;
  t0 = std::fmod(std::fmod(t0, 90.0) + 90.0, 90.0);
  return {t0, 2 * amp / (s0 + amp)};
}

// The stage angle at which the computed section extinguishes: a vibration direction at angle φ
// (counter-clockwise from east) at stage 0 is at φ + θ after turning the stage by θ, and
// extinction needs it E–W or N–S. The feature (north) is at 90°, so φ_slow = 90° + to_slow.
double predicted_stage_deg(const Cut& c, const glm::dvec3& feature) {
  const Extinction e = extinction_from(optics_of(c), feature);
  return std::fmod(std::fmod(-e.to_slow_deg, 90.0) + 90.0, 90.0);
}

double mod90_distance(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 90.0);
  return std::min(d, 90.0 - d);
}

// The extinction angle to the north feature from a stage angle of extinction: the nearer of the
// two vibration directions, in [0, 45].
double extinction_angle_from_stage(double stage_deg) { return std::min(stage_deg, 90.0 - stage_deg); }

glm::dvec3 north_of(const Cut& c) {
  const MineralCrystallography& m = *find_mineral_crystallography(c.mineral);
  return lattice_direction(m.cell, parse_lattice_direction(c.north));
}

}  // namespace

// Tolerance of the measurement: 0.05°. In parallel monochromatic light at normal incidence the
// rendered brightness follows the sin² law exactly (a plate's eigenmodes at normal incidence
// vibrate along the axes of the central section), so the Fourier fit is exact up to the float
// accumulation of the image (1e-7 relative, i.e. ~1e-6° in θ0), and the parabola refinement moves
// a minimum that is off by δ by less than δ·h²·(16/12) ≈ 5e-4·δ for h = 1° (the quartic term of
// 1 − cos 4x). 0.05° is far above both and far below the published spreads (several degrees), so
// a wrong orientation (side, axis, cut frame) cannot pass.
TEST(ExtinctionFromRenders, MonoclinicPrismsCutParallelTo010WithCNorth) {
  struct Case {
    Cut cut;
    double lo_deg, hi_deg;
  };
  // Published ranges of Z ∧ c (the extinction angle to the c trace and to the {110} cleavage
  // traces, which are ∥ c in (010)): augite 35–48° (DHZ), diopside 38–48° (DHZ), hornblende
  // 12–34° (DHZ).
  for (const Case& k :
       {Case{{"augite", "(010)", "[001]"}, 35, 48}, Case{{"diopside", "(010)", "[001]"}, 38, 48},
        Case{{"hornblende", "(010)", "[001]"}, 12, 34}}) {
    const Measured m = measure_extinction(k.cut);
    const double predicted = predicted_stage_deg(k.cut, north_of(k.cut));
    EXPECT_LT(mod90_distance(m.stage_deg, predicted), 0.05)
        << k.cut.mineral << ": rendered " << m.stage_deg << "°, computed " << predicted << "°";
    const double angle = extinction_angle_from_stage(m.stage_deg);
    // Inside the published range, to the measurement tolerance (diopside's 38° is the end point).
    EXPECT_GE(angle, k.lo_deg - 0.05) << k.cut.mineral;
    EXPECT_LE(angle, k.hi_deg + 0.05) << k.cut.mineral;
    EXPECT_GT(m.contrast, 0.99) << k.cut.mineral;  // a real extinction, not a flat curve
    std::printf(
        "%-10s (010), [001] north: extinction at stage %.4f°, extinction angle %.4f° "
        "(computed %.4f°; published %g–%g°)\n",
        k.cut.mineral, m.stage_deg, angle, extinction_angle_from_stage(predicted), k.lo_deg, k.hi_deg);
  }
}

// Orthopyroxene: parallel extinction in prismatic sections (Nesse 2012; DHZ). Tolerance 0.05° as
// above.
TEST(ExtinctionFromRenders, EnstatiteExtinguishesParallelToC) {
  for (const Cut& c : {Cut{"enstatite", "(010)", "[001]"}, Cut{"enstatite", "(100)", "[001]"},
                       Cut{"enstatite", "(210)", "[001]"}}) {
    const Measured m = measure_extinction(c);
    EXPECT_LT(extinction_angle_from_stage(m.stage_deg), 0.05) << c.plane;
    std::printf("enstatite %s, [001] north: extinction angle %.4f° (published: parallel)\n", c.plane,
                extinction_angle_from_stage(m.stage_deg));
  }
}

// Micas in sections ⟂ (001) with the cleavage trace north: parallel or nearly parallel
// extinction, "up to a few degrees" (Nesse 2012: muscovite 0–3°; biotite nearly parallel). In
// (010) the (001) trace is [100].
TEST(ExtinctionFromRenders, MicasNearlyParallelToTheCleavageTrace) {
  for (const Cut& c : {Cut{"muscovite", "(010)", "[100]"}, Cut{"biotite", "(010)", "[100]"},
                       Cut{"muscovite", "(100)", "[010]"}}) {
    const Measured m = measure_extinction(c);
    const double predicted = predicted_stage_deg(c, north_of(c));
    EXPECT_LT(mod90_distance(m.stage_deg, predicted), 0.05) << c.mineral << " " << c.plane;
    const double angle = extinction_angle_from_stage(m.stage_deg);
    EXPECT_LE(angle, 3.5) << c.mineral << " " << c.plane;
    std::printf(
        "%-10s %s, %s north: extinction angle to the (001) trace %.4f° (computed %.4f°; "
        "published 0 to ~3°)\n",
        c.mineral, c.plane, c.north, angle, extinction_angle_from_stage(predicted));
  }
}

// (d) A cut equivalent to typed axes gives the same image, bit for bit: olivine (Pbnm: X = b,
// Y = c, Z = a) cut ∥ (010) with [001] north has X along the stage normal and Z = a along east ×
// −1 (north × normal = c × b = −a); quartz cut ∥ (1-100) with [001] north has its optic axis north.
TEST(ExtinctionFromRenders, ACutRendersLikeTheAxesItAmountsTo) {
  Scene cut = plate_scene({"olivine", "(010)", "[001]"}, 30.0);
  Scene axes = cut;
  axes.sample.cut.reset();
  axes.sample.x_axis = {0, 0, 1};
  axes.sample.z_axis = {-1, 0, 0};
  axes.render.single_wavelength_nm = cut.render.single_wavelength_nm = 0;  // white light
  EXPECT_EQ(ProgressiveRenderer::render(cut, 1).rgb, ProgressiveRenderer::render(axes, 1).rgb);

  Scene qcut;
  qcut.sample.mineral = "quartz";
  qcut.sample.cut = SampleCut{"(1-100)", "[001]"};
  qcut.stage_deg = 20;
  qcut.render.width = qcut.render.height = 4;
  qcut.render.spp = 1;
  Scene qaxes = qcut;
  qaxes.sample.cut.reset();
  qaxes.sample.optic_axis = {0, 1, 0};
  EXPECT_EQ(ProgressiveRenderer::render(qcut, 1).rgb, ProgressiveRenderer::render(qaxes, 1).rgb);
}
