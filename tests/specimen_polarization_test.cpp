// The polarization-exact specimen tracer (core/specimen/jones_path.h) against closed forms:
// interference between crossed polars, extinction, energy per Fresnel event, the isotropic limit
// (today's plane-light image), degenerate modes along an optic axis, pleochroic Beer–Lambert.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/crystal/section_optics.h"
#include "core/materials/medium.h"
#include "core/specimen/forward_plane_light.h"
#include "core/specimen/jones_path.h"
#include "core/specimen/plane_light_image.h"
#include "core/specimen/specimen_random.h"
#include "core/specimen/specimen_scene.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "tests/specimen_fixture.h"

namespace {

using pmsim::kPi;
constexpr double kLambda = 589.26;
constexpr double kLiquid = 1.54;

// One smooth, flat-topped fragment (superellipsoid exponent 16, no lobes) centred at the origin:
// within 20 µm of its centre its faces are horizontal to ~1e-9 rad, a plate seen at normal
// incidence.
std::unique_ptr<pmsim::SpecimenScene> flat_fragment(const pmsim::Crystal& c, const glm::dmat3& orientation,
                                                    double size_um = 120.0) {
  pmsim::FragmentShape shape;
  shape.size_um = size_um;
  shape.roughness = 0.0;
  shape.flatness = 16.0;
  shape.height_ratio = 0.4;
  shape.crystal_to_lab = orientation;
  return std::make_unique<pmsim::SpecimenScene>(std::vector<pmsim::FragmentShape>{shape}, c,
                                                pmsim::immersion_liquid(kLiquid, 0.0),
                                                pmsim::find_medium("N-BK7"), pmsim::find_medium("air"));
}

// The fragment's thickness on the vertical through (x, y): its top and bottom hits.
double thickness_at(const pmsim::SpecimenScene& s, double x, double y) {
  glm::dvec3 o{x, y, s.cover_top_z_um() + 10.0};
  const glm::dvec3 d{0.0, 0.0, -1.0};
  pmsim::SpecimenHit h;
  double top = 0.0, bottom = 0.0;
  bool in = false;
  for (int i = 0; i < 8 && s.intersect(o, d, 1e-4, h); ++i) {
    if (h.back >= pmsim::kFirstFragment && !in) {
      top = h.point.z;
      in = true;
    } else if (h.back >= pmsim::kFirstFragment && in) {
      bottom = h.point.z;
      break;
    }
    o = h.point;
  }
  return top - bottom;
}

// A vertical ray at (x, y), polarizer along x, analyzer along `analyzer_rad` (or out).
pmsim::JonesPath vertical(const pmsim::SpecimenScene& s, double x, double y, bool analyzer_in,
                          double analyzer_rad = kPi / 2, double polarizer_rad = 0.0,
                          pmsim::InterfaceCounters* c = nullptr) {
  pmsim::JonesPathRequest q;
  q.origin = {x, y, s.cover_top_z_um() + 10.0};
  q.dir = {0.0, 0.0, -1.0};
  q.wavelength_nm = kLambda;
  q.starts = analyzer_in ? 1 : 2;
  q.start_vibration = analyzer_in ? glm::dvec3(std::cos(analyzer_rad), std::sin(analyzer_rad), 0.0)
                                  : glm::dvec3(std::cos(polarizer_rad), std::sin(polarizer_rad), 0.0);
  q.polarizer = {std::cos(polarizer_rad), std::sin(polarizer_rad), 0.0};
  return pmsim::trace_specimen_jones(s, q, c);
}

// The same vertical path traced forward (core/specimen/forward_plane_light.h): from the air below
// the slide, up, with the polarizer's vibration; the exits' powers summed (analyzer in: their
// shares of the coherent sum at the analyzer).
double vertical_forward(const pmsim::SpecimenScene& s, double x, double y, bool analyzer_in,
                        double analyzer_rad = kPi / 2) {
  pmsim::JonesPathRequest q;
  q.forward = true;
  q.origin = {x, y, -s.layers().slide_um - 5.0};
  q.dir = {0.0, 0.0, 1.0};
  q.wavelength_nm = kLambda;
  q.starts = 1;
  q.start_vibration = q.polarizer = {1.0, 0.0, 0.0};
  q.forward_analyzer_in = analyzer_in;
  q.forward_analyzer = {std::cos(analyzer_rad), std::sin(analyzer_rad), 0.0};
  const pmsim::JonesPath p = pmsim::trace_specimen_jones(s, q);
  double sum = 0.0;
  for (int i = 0; i < p.n_exits; ++i) sum += p.exits[std::size_t(i)].power;
  return sum;
}

double normal_R(double n1, double n2) { return std::pow((n1 - n2) / (n1 + n2), 2); }

// Crossed polars at normal incidence through a plate in a liquid, polarizer at φ to the fast
// vibration: the two modes, of power transmittances τ_k = (1 − R_k)² through the plate's two faces
// and phase difference δ = 2πΓ/λ, recombine at the analyzer to
//   I/T_stack = sin²2φ/4 · |√τ_f − √τ_s e^{iδ}|² = sin²2φ·[(√τ_f − √τ_s)²/4 + √(τ_f τ_s)·sin²(πΓ/λ)],
// the textbook sin²2φ·sin²(πΓ/λ) (Born & Wolf §15.4.2) with the faces' Fresnel losses.
double crossed_closed_form(double phi, double n_fast, double n_slow, double thickness_um, double lambda_nm = kLambda) {
  const double tf = 1.0 - normal_R(n_fast, kLiquid), ts = 1.0 - normal_R(n_slow, kLiquid);  // amplitudes √τ
  const double gamma_nm = (n_slow - n_fast) * thickness_um * 1000.0;
  const double s2 = std::pow(std::sin(2.0 * phi), 2);
  return s2 * ((tf - ts) * (tf - ts) / 4.0 + tf * ts * std::pow(std::sin(kPi * gamma_nm / lambda_nm), 2));
}

struct PlateCase {
  double no, ne;
};

// (a) A flat uniaxial fragment, optic axis horizontal at φ to the polarizer, between crossed
// polars: I follows the closed form for a weakly birefringent quartz-like crystal (Γ a fraction of
// a wave) and for calcite (Γ ≈ 8 µm, 14 waves: the unwrapped double phase must keep it exact).
// Tolerance 1e-6 of the empty field: the faces are horizontal to ~1e-9 rad and the phase is
// exact to ~1e-12 rad; what is left is the float rounding of the mesh's hit points (1e-7 µm of
// thickness ↔ 1e-6 rad of phase for calcite).
TEST(SpecimenPolarization, CrossedPolarsGiveSin2PhiSinPiGammaOverLambda) {
  for (const PlateCase pc : {PlateCase{1.5443, 1.5534}, PlateCase{1.6584, 1.4864}}) {
    const pmsim::Crystal c = pmsim::Crystal::uniaxial_constant("plate", pc.no, pc.ne);
    const double n_fast = std::min(pc.no, pc.ne), n_slow = std::max(pc.no, pc.ne);
    for (const double phi_deg : {0.0, 10.0, 22.5, 45.0, 67.0, 90.0}) {
      const double phi = pmsim::radians(phi_deg);
      const glm::dvec3 axis{std::cos(phi), std::sin(phi), 0.0};
      const auto s = flat_fragment(c, pmsim::uniaxial_orientation(axis));
      const double L = thickness_at(*s, 1.0, 2.0);
      ASSERT_GT(L, 30.0);
      // The empty field's transmission: a vertical ray beside the fragment, analyzer out.
      const double T_stack = vertical(*s, 200.0, 0.0, false).intensity(2);
      const double I = vertical(*s, 1.0, 2.0, true).intensity(1) / T_stack;
      // φ is measured from the polarizer to the optic axis; sin²2φ is the same from either mode.
      const double expected = crossed_closed_form(phi, n_fast, n_slow, L);
      EXPECT_NEAR(I, expected, 1e-6) << "no " << pc.no << " ne " << pc.ne << " φ " << phi_deg << "° Γ "
                                     << (n_slow - n_fast) * L * 1000.0 << " nm";
      if (phi_deg == 0.0 || phi_deg == 90.0) {  // an indicatrix axis along the polarizer: extinct
        EXPECT_LT(I, 1e-20);
      }
    }
  }
}

// (a, forward) Reciprocity at the path level: the same plates traced forward from the polarizer
// to the analyzer give the same closed form, to the same 1e-6 (the backward path's tolerance:
// float hit points of the mesh), and extinction below 1e-20 with an indicatrix axis along the
// polarizer.
TEST(SpecimenPolarization, ForwardPathsGiveTheSameCrossedPolarIntensity) {
  for (const PlateCase pc : {PlateCase{1.5443, 1.5534}, PlateCase{1.6584, 1.4864}}) {
    const pmsim::Crystal c = pmsim::Crystal::uniaxial_constant("plate", pc.no, pc.ne);
    const double n_fast = std::min(pc.no, pc.ne), n_slow = std::max(pc.no, pc.ne);
    for (const double phi_deg : {0.0, 22.5, 45.0, 67.0}) {
      const double phi = pmsim::radians(phi_deg);
      const auto s = flat_fragment(c, pmsim::uniaxial_orientation({std::cos(phi), std::sin(phi), 0.0}));
      const double L = thickness_at(*s, 1.0, 2.0);
      const double T_stack = vertical_forward(*s, 200.0, 0.0, false);
      const double I = vertical_forward(*s, 1.0, 2.0, true) / T_stack;
      EXPECT_NEAR(I, crossed_closed_form(phi, n_fast, n_slow, L), 1e-6) << "no " << pc.no << " φ " << phi_deg;
      if (phi_deg == 0.0) {
        EXPECT_LT(I, 1e-20);
      }
    }
  }
}

// (a') A biaxial plate: the retardation of the section is computed from the indicatrix
// (section_optics), not typed in. Olivine-like indices, the section ⟂ X (so n′ = nβ, nγ).
TEST(SpecimenPolarization, BiaxialSectionRetardationFromTheIndicatrix) {
  const pmsim::Crystal c = pmsim::Crystal::biaxial_constant("ol", 1.651, 1.670, 1.689);
  // Crystal X vertical, Y at 30° from the polarizer.
  const double a = pmsim::radians(30.0);
  const glm::dmat3 R = pmsim::biaxial_orientation({0.0, 0.0, 1.0}, {-std::sin(a), std::cos(a), 0.0});
  const auto s = flat_fragment(c, R);
  const double L = thickness_at(*s, 0.0, 0.0);
  const pmsim::SectionOptics so = pmsim::section_optics(R, c.principal_indices(kLambda), {0.0, 0.0, 1.0});
  const double phi = std::atan2(so.fast.y, so.fast.x);
  const double T_stack = vertical(*s, 200.0, 0.0, false).intensity(2);
  const double I = vertical(*s, 0.0, 0.0, true).intensity(1) / T_stack;
  EXPECT_NEAR(so.n_slow - so.n_fast, 1.689 - 1.670, 1e-12);
  EXPECT_NEAR(I, crossed_closed_form(phi, so.n_fast, so.n_slow, L), 1e-6);
}

namespace {

// The plate of (a'') rendered by `render` at `spp`: its mean colour against the spectral integral.
struct PlateColour {
  glm::dvec3 mean{0.0}, expected{0.0};
  double de = 0.0, gamma_nm = 0.0;
  int wavelengths = 0;
};
PlateColour plate_colour(pmsim::RenderImage (*render)(const pmsim::SpecimenScene&, const pmsim::PlaneLightOptions&,
                                                      const std::function<void(const pmsim::RenderImage&)>&,
                                                      pmsim::InterfaceCounters*, const std::atomic<bool>*),
                         int spp) {
  const double no = 1.54, ne = 1.56;
  const pmsim::Crystal c = pmsim::Crystal::uniaxial_constant("plate", no, ne);
  const auto s = flat_fragment(c, pmsim::uniaxial_orientation({std::sqrt(0.5), std::sqrt(0.5), 0.0}));
  const double L = thickness_at(*s, 0.0, 0.0);
  pmsim::PlaneLightOptions o;
  o.width = o.height = 12;
  o.um_per_px = 1.0;
  o.objective_na = 0.05;
  o.analyzer_in = true;
  o.spp = spp;
  const pmsim::RenderImage img = render(*s, o, nullptr, nullptr, nullptr);
  PlateColour r;
  r.wavelengths = img.wavelengths;
  r.gamma_nm = (ne - no) * L * 1000.0;
  for (int i = 0; i < o.width * o.height; ++i)
    r.mean += glm::dvec3(img.xyz[3 * i], img.xyz[3 * i + 1], img.xyz[3 * i + 2]) / double(o.width * o.height);
  for (double l = pmsim::kVisibleMinNm + 0.5; l < pmsim::kVisibleMaxNm; l += 1.0)
    r.expected += crossed_closed_form(kPi / 4, no, ne, L, l) * pmsim::observer_weight(pmsim::Illuminant::D65, l);
  const glm::dvec3 white = pmsim::illuminant_white_xyz(pmsim::Illuminant::D65);
  r.de = pmsim::ciede2000(pmsim::xyz_to_lab(r.mean, white), pmsim::xyz_to_lab(r.expected, white));
  return r;
}

}  // namespace

// (a'') The converged colour: a plate of Γ ≈ 960 nm (second-order blue-green) at 45° between
// crossed polars in white light (D65), rendered with the analyzer in (32 bands, λ stratified within
// each), against XYZ = ∫ I(λ)·w(λ) dλ of the closed form at 1 nm. A 12 µm patch at the plate's
// centre, objective NA 0.05 and the condenser stopped down (rays within 3° of the normal change Γ
// by < 0.1%). Tolerance ΔE00 ≤ 1 (one just-noticeable difference): measured 0.28 (seed 1), 0.44
// (seed 2); 64 bands give 0.13, so ~0.15 is the 12.5 nm bands' averaging of sin² within a band
// and the rest sampling noise. Y within 0.005 (measured 0.0001–0.0008): a band-weight sum off by
// 4% (1 nm steps that cover 12 of a band's 12.5 nm, the bug this caught) fails it.
TEST(SpecimenPolarization, WhiteLightInterferenceColourConvergesToTheSpectralIntegral) {
  const PlateColour r = plate_colour(pmsim::render_plane_light, 256);
  RecordProperty("delta_e00", std::to_string(r.de));
  EXPECT_EQ(r.wavelengths, pmsim::kCrossedPolarBands);
  EXPECT_NEAR(r.mean.y, r.expected.y, 0.005);
  EXPECT_LT(r.de, 1.0) << "Γ " << r.gamma_nm << " nm; rendered Y " << r.mean.y << ", closed form Y " << r.expected.y;
}

// (a'', forward) The same plate's colour rendered forward from the condenser, as the thin sections
// are: 32 bands on a subgrid of period 4, 4 λ a band a pass (forward_plane_light.h). Same
// tolerances and reasons as above; the plate is flat, so every pass is exact but for the λ
// sampling within the bands: measured ΔE00 0.38, 0.23, 0.42 (seeds 1–3) at 64 traces a pixel
// (22 passes), against the backward renderer's 0.28–0.44 at 256.
TEST(SpecimenPolarization, ForwardWhiteLightInterferenceColourConvergesToTheSpectralIntegral) {
  const PlateColour r = plate_colour(pmsim::render_plane_light_forward, 64);
  RecordProperty("delta_e00", std::to_string(r.de));
  EXPECT_EQ(r.wavelengths, pmsim::kCrossedPolarBands);
  EXPECT_NEAR(r.mean.y, r.expected.y, 0.005);
  EXPECT_LT(r.de, 1.0) << "Γ " << r.gamma_nm << " nm; rendered Y " << r.mean.y << ", closed form Y " << r.expected.y;
}

// (b) Energy: every Fresnel event, of either mode, conserves R + T = 1 to rounding (1e-12
// relative), over rays at all angles of an NA 0.95 cone through a calcite fragment, including its
// edge where the modes are totally reflected.
TEST(SpecimenPolarization, EveryFresnelEventConservesPowerForBothModes) {
  const pmsim::Crystal& calcite = pmsim::find_mineral("calcite");
  const auto s = flat_fragment(calcite, pmsim::uniaxial_orientation({0.3, 0.5, 0.8}));
  pmsim::InterfaceCounters c;
  pmsim::SpecimenRandom rng(7);
  int split = 0;
  double max_I = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double sin_t = 0.95 * std::sqrt(rng.uniform()), phi = 2.0 * kPi * rng.uniform();
    const glm::dvec3 d{sin_t * std::cos(phi), sin_t * std::sin(phi), -std::sqrt(1.0 - sin_t * sin_t)};
    const glm::dvec3 focus{140.0 * (rng.uniform() - 0.5), 140.0 * (rng.uniform() - 0.5), 20.0};
    pmsim::JonesPathRequest q;
    q.origin = focus + ((s->cover_top_z_um() + 10.0 - focus.z) / d.z) * d;
    q.dir = d;
    q.wavelength_nm = 400.0 + 350.0 * rng.uniform();
    q.starts = 2;
    q.start_vibration = {1.0, 0.0, 0.0};
    q.polarizer = {std::cos(phi), std::sin(phi), 0.0};
    const pmsim::JonesPath p = pmsim::trace_specimen_jones(*s, q, &c);
    split += p.leaves > 1;
    ASSERT_TRUE(std::isfinite(p.intensity(2)));
    max_I = std::max(max_I, p.intensity(2));
  }
  RecordProperty("max_plane_light_intensity", std::to_string(max_I));
  RecordProperty("capped_power_per_path", std::to_string(c.capped_power / c.paths));
  // (No bound I ≤ 1: branches leaving in different directions collect light from different
  // points of the source, as rays crowding into a Becke line do.)
  EXPECT_GT(split, 1000) << "rays through the fragment split into two modes";
  EXPECT_GT(c.tir, 0u) << "the fragment's edge reflects some modes totally";
  EXPECT_LT(c.max_defect, 1e-12);
  EXPECT_NEAR(c.reflected + c.transmitted, c.incident, 1e-12 * c.incident);
  // The 8-leaf cap is reached only by rays trapped near grazing in the rim (seen: 1.6e-5 of a
  // path's power per path at NA 0.95).
  EXPECT_LT(c.capped_power, 1e-4 * double(c.paths));
}

// (c) The isotropic limit: a fragment of n = 1.60 in plane light, the polarization-exact tracer
// against the one-vibration tracer on the same samples (same seed: the same pixels, pupil points
// and λ). They differ only by the s/p mixing of the oblique Fresnel events, second order in the
// angles: the mean |difference| must be below a quarter of the Monte Carlo noise (the mean
// |difference| between two seeds of the scalar tracer), and the images' means agree to 1e-3.
TEST(SpecimenPolarization, IsotropicFragmentMatchesTheScalarTracer) {
  specimen_test::OneFragment f;
  const auto s = specimen_test::make_specimen(f);
  pmsim::PlaneLightOptions o = specimen_test::mono_view(10.0, 16);
  o.scalar_tracer = true;
  const pmsim::RenderImage scalar = pmsim::render_plane_light(*s, o);
  o.seed = 2;
  const pmsim::RenderImage scalar2 = pmsim::render_plane_light(*s, o);
  o.seed = 1;
  o.scalar_tracer = false;
  const pmsim::RenderImage exact = pmsim::render_plane_light(*s, o);
  double d_exact = 0.0, d_noise = 0.0, m_exact = 0.0, m_scalar = 0.0;
  const std::size_t n = std::size_t(o.width) * o.height;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = exact.xyz[3 * i + 1], b = scalar.xyz[3 * i + 1], b2 = scalar2.xyz[3 * i + 1];
    ASSERT_TRUE(std::isfinite(a));
    d_exact += std::abs(a - b);
    d_noise += std::abs(b2 - b);
    m_exact += a;
    m_scalar += b;
  }
  RecordProperty("mean_abs_diff_exact_vs_scalar", std::to_string(d_exact / n));
  RecordProperty("mean_abs_diff_two_seeds", std::to_string(d_noise / n));
  EXPECT_LT(d_exact, 0.25 * d_noise) << d_exact / n << " vs noise " << d_noise / n;
  EXPECT_NEAR(m_exact / n, m_scalar / n, 1e-3);
}

// (e) Degenerate modes: a ray along an optic axis (uniaxial c vertical; a biaxial optic axis
// vertical) meets a circular section; the tracer must stay finite and, with no retardation,
// extinct between crossed polars at every stage angle (I < 1e-20 of the empty field: the only
// leak is the rounding of directions ~1e-16).
TEST(SpecimenPolarization, OpticAxisAndCriticalAngleStayFinite) {
  const pmsim::Crystal& calcite = pmsim::find_mineral("calcite");
  const auto u = flat_fragment(calcite, pmsim::uniaxial_orientation({0.0, 0.0, 1.0}));
  const pmsim::Crystal ol = pmsim::Crystal::biaxial_constant("ol", 1.651, 1.670, 1.689);
  const double vz = 0.5 * pmsim::optic_angle_2v_rad(1.651, 1.670, 1.689);
  // Crystal Z at −Vz from lab z in the xz plane: the optic axis (sin Vz, 0, cos Vz) is vertical.
  const glm::dmat3 R = pmsim::biaxial_orientation({std::cos(vz), 0.0, std::sin(vz)}, {-std::sin(vz), 0.0, std::cos(vz)});
  ASSERT_NEAR(glm::length(R * glm::dvec3(std::sin(vz), 0.0, std::cos(vz)) - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
  const auto b = flat_fragment(ol, R);
  struct Case {
    const pmsim::SpecimenScene* scene;
    double n_axis;  // the index of both modes along the optic axis: nω, nβ
  };
  for (const Case cs : {Case{u.get(), calcite.principal_indices(kLambda).x}, Case{b.get(), 1.670}}) {
    const pmsim::SpecimenScene* s = cs.scene;
    const double T_stack = vertical(*s, 200.0, 0.0, false).intensity(2);
    for (const double stage_deg : {0.0, 17.0, 45.0, 80.0}) {
      const double p = pmsim::radians(stage_deg);
      const pmsim::JonesPath path = vertical(*s, 0.0, 0.0, true, p + kPi / 2, p);
      ASSERT_TRUE(std::isfinite(path.intensity(1)));
      EXPECT_LT(path.intensity(1) / T_stack, 1e-20) << "stage " << stage_deg;
      const double I_out = vertical(*s, 0.0, 0.0, false, kPi / 2, p).intensity(2);
      // Analyzer out: the plate's two faces' Fresnel loss at the axis index, whatever the
      // (arbitrary) split of the circular section into two modes.
      EXPECT_NEAR(I_out / T_stack, std::pow(1.0 - normal_R(cs.n_axis, kLiquid), 2), 1e-9);
    }
  }
  // Around the critical angle: rays grazing along the cover glass and into the fragment's rim,
  // a fine sweep of angles through the critical angle of the rim's inner faces (calcite and
  // liquid: sinθc = 1.54/1.66 for ω). Every intensity finite.
  for (int i = 0; i <= 4000; ++i) {
    const double sin_t = 0.999999 * i / 4000.0;
    const glm::dvec3 d{sin_t, 0.0, -std::sqrt(1.0 - sin_t * sin_t)};
    pmsim::JonesPathRequest q;
    q.origin = glm::dvec3(55.0, 0.0, 20.0) + ((u->cover_top_z_um() + 10.0 - 20.0) / d.z) * d;
    q.dir = d;
    q.wavelength_nm = kLambda;
    q.starts = 2;
    const pmsim::JonesPath p = pmsim::trace_specimen_jones(*u, q);
    ASSERT_TRUE(std::isfinite(p.intensity(2))) << sin_t;
  }
}

// (f) Pleochroism: a biotite-like plate (μ_X ≠ μ_Y, section ⟂ Z so X, Y lie in the plane), plane
// light (analyzer out) along X and along Y: I/T_stack = (1 − R)²·exp(−μ·L), Beer–Lambert along the
// mode's vibration with the two faces' Fresnel losses. Tolerance 1e-9 relative (closed form at
// normal incidence; nothing but rounding differs).
TEST(SpecimenPolarization, PleochroicPlateFollowsBeerLambertAlongTheMode) {
  pmsim::Crystal c = pmsim::Crystal::biaxial_constant("biotite-like", 1.595, 1.640, 1.641);
  const double mu_x = 0.002, mu_y = 0.03;  // per µm: pale along X, dark brown along Y
  c.set_absorption({{400.0, 800.0}, {mu_x, mu_x}}, {{400.0, 800.0}, {mu_y, mu_y}}, {{400.0, 800.0}, {mu_y, mu_y}});
  const double a = pmsim::radians(20.0);  // X at 20° from lab x
  const glm::dmat3 R = pmsim::biaxial_orientation({std::cos(a), std::sin(a), 0.0}, {0.0, 0.0, 1.0});
  const auto s = flat_fragment(c, R);
  const double L = thickness_at(*s, 0.0, 0.0);
  const double T_stack = vertical(*s, 200.0, 0.0, false).intensity(2);
  const double I_x = vertical(*s, 0.0, 0.0, false, 0.0, a).intensity(2) / T_stack;
  const double I_y = vertical(*s, 0.0, 0.0, false, 0.0, a + kPi / 2).intensity(2) / T_stack;
  const double e_x = std::pow(1.0 - normal_R(1.595, kLiquid), 2) * std::exp(-mu_x * L);
  const double e_y = std::pow(1.0 - normal_R(1.640, kLiquid), 2) * std::exp(-mu_y * L);
  EXPECT_NEAR(I_x, e_x, 1e-9 * e_x);
  EXPECT_NEAR(I_y, e_y, 1e-9 * e_y);
  // Between the two: the polarizer at 45° to X sees both modes' powers, half each (analyzer out,
  // the modes' phases do not matter).
  const double I_45 = vertical(*s, 0.0, 0.0, false, 0.0, a + kPi / 4).intensity(2) / T_stack;
  EXPECT_NEAR(I_45, 0.5 * (e_x + e_y), 1e-9);
}

}  // namespace
