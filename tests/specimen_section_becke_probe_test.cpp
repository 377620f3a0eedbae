// The teaching panel's Becke-line probe for thin sections (core/specimen/section_becke_probe.h):
// it finds the nearest boundary between two media of the section slab, names the media on each
// side with the index each offers along the polarizer (the indicatrix's radius, from the same
// crystals, orientations and mounting medium the slab tracer is given), and reports that the line
// moves into the side of higher index on focusing up (the physics the grain-mount probe test
// checks against the traced image, tests/specimen_becke_probe_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/crystal/crystal.h"
#include "core/microscope/map_section.h"
#include "core/microscope/section_map.h"
#include "core/specimen/becke_probe.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/probe_point.h"
#include "core/specimen/section_becke_probe.h"
#include "core/specimen/section_slab.h"
#include "core/specimen/specimen_scene.h"

namespace {

using pmsim::BeckeMovesInto;
using pmsim::SectionMap;

constexpr double kLambdaD = 589.26;

// A grain of `crystal` in orientation `axes` (indicatrix columns X, Y, Z in the section frame),
// centred at `centre_mm`, a circle of radius `radius_mm` as its shape ellipse.
pmsim::SectionGrain grain(const pmsim::Crystal* crystal, glm::dvec2 centre_mm, double radius_mm,
                          const glm::dmat3& axes = glm::dmat3(1.0)) {
  pmsim::SectionGrain g;
  g.mineral = crystal->name();
  g.crystal = crystal;
  g.orientation = g.twin_orientation = axes;
  g.centre_mm = centre_mm;
  g.semi_major_mm = g.semi_minor_mm = radius_mm;
  g.metric_xx = g.metric_yy = 1.0 / (radius_mm * radius_mm);
  pmsim::SectionZone z;
  z.mineral = g.mineral;
  z.crystal = crystal;
  z.orientation = z.twin_orientation = axes;
  g.zones.push_back(z);
  return g;
}

// Two equal grains side by side in a 200 µm × 200 µm section: `west` centred 50 µm west of the
// origin, `east` 50 µm east. Equal shape ellipses tile along their perpendicular bisector, x = 0.
std::shared_ptr<SectionMap> two_grain_section(const pmsim::Crystal* west, const pmsim::Crystal* east) {
  auto m = std::make_shared<SectionMap>();
  m->name = "two grains";
  m->width_mm = m->height_mm = 0.2;
  m->grains.push_back(grain(west, {-0.05, 0.0}, 0.1));
  m->grains.push_back(grain(east, {0.05, 0.0}, 0.1));
  m->finish();
  return m;
}

// One grain filling a 120 µm square section; beyond its edge (x or y = ±60 µm) the mounting medium.
std::shared_ptr<SectionMap> one_grain_section(const pmsim::Crystal* c,
                                              const glm::dmat3& axes = glm::dmat3(1.0)) {
  auto m = std::make_shared<SectionMap>();
  m->name = "one grain";
  m->width_mm = m->height_mm = 0.12;
  m->grains.push_back(grain(c, {0.0, 0.0}, 0.12, axes));
  m->finish();
  return m;
}

// 100× objective, 200 px: a 0.2 mm field of 1 µm pixels around the stage position.
pmsim::Scene section_scene(double polarizer_deg = 0.0, double stage_deg = 0.0) {
  pmsim::Scene s;
  s.sample.type = pmsim::SampleType::Section;
  s.analyzer_in = false;
  s.objective.magnification = 100.0;
  s.render.width = s.render.height = 200;
  s.polarizer_deg = polarizer_deg;
  s.stage_deg = stage_deg;
  return s;
}

// The image fractions of specimen point p (µm) at stage angle 0, centre `stage`.
glm::dvec2 fractions(const pmsim::Scene& s, glm::dvec2 p_um) {
  const pmsim::PlaneLightOptions o = pmsim::plane_light_options(s);
  return {0.5 + (p_um.x - o.centre_um.x) / (o.width * o.um_per_px),
          0.5 - (p_um.y - o.centre_um.y) / (o.height * o.um_per_px)};
}

pmsim::SectionBeckeProbe probe_at(const SectionMap& m, const pmsim::Scene& s, glm::dvec2 p_um) {
  const glm::dvec2 f = fractions(s, p_um);
  return pmsim::probe_section_becke_line(m, s, f.x, f.y);
}

}  // namespace

// A grain of n = 1.70 against one of n = 1.55 (isotropic, no dispersion): from 10 µm inside
// either grain the probe finds their common boundary x = 0 and names the 1.70 grain as the side
// the line moves into on focusing up.
TEST(SectionBeckeProbe, GrainBoundaryNamesTheHigherIndexSide) {
  const pmsim::Crystal high = pmsim::Crystal::isotropic_constant("high", 1.70);
  const pmsim::Crystal low = pmsim::Crystal::isotropic_constant("low", 1.55);
  const auto map = two_grain_section(&high, &low);
  const pmsim::Scene scene = section_scene();
  ASSERT_NEAR(pmsim::probe_point(scene, fractions(scene, {-10.0, 0.0}).x, 0.5).specimen_um.x, -10.0, 1e-9);

  const pmsim::SectionBeckeProbe w = probe_at(*map, scene, {-10.0, 0.0});
  ASSERT_TRUE(w.found);
  EXPECT_EQ(w.here.grain, 1);
  EXPECT_EQ(w.here.mineral, "high");
  EXPECT_EQ(w.there.grain, 2);
  EXPECT_EQ(w.there.mineral, "low");
  // Constant indices: exact up to rounding.
  EXPECT_NEAR(w.here.n, 1.70, 1e-12);
  EXPECT_NEAR(w.there.n, 1.55, 1e-12);
  EXPECT_EQ(w.moves_into, BeckeMovesInto::Here);
  // The boundary is the line x = 0, 10 µm east; the search's direction 0° points straight at
  // it and bisects to 1e-4 µm (the nearest other boundary, the section's edge, is 90 µm away).
  EXPECT_NEAR(w.distance_um, 10.0, 1e-3);
  EXPECT_NEAR(w.boundary_um.x, 0.0, 1e-3);
  EXPECT_NEAR(w.boundary_um.y, 0.0, 1e-3);

  const pmsim::SectionBeckeProbe e = probe_at(*map, scene, {7.0, 3.0});
  ASSERT_TRUE(e.found);
  EXPECT_EQ(e.here.mineral, "low");
  EXPECT_EQ(e.there.mineral, "high");
  EXPECT_EQ(e.moves_into, BeckeMovesInto::There);
  // 7 µm from x = 0 along the 2°-spaced direction 180°: exact to the bisection.
  EXPECT_NEAR(e.distance_um, 7.0, 1e-3);
  const std::string text = pmsim::describe_section_becke_line(e);
  std::printf("%s\n", text.c_str());
  EXPECT_NE(text.find("moves into the high (grain 1)"), std::string::npos) << text;
  EXPECT_NE(text.find("low (grain 2)"), std::string::npos) << text;

  // Two grains of equal index: matched, no line.
  const pmsim::Crystal low2 = pmsim::Crystal::isotropic_constant("low too", 1.5505);
  const auto matched = two_grain_section(&low2, &low);
  EXPECT_EQ(probe_at(*matched, scene, {-10.0, 0.0}).moves_into, BeckeMovesInto::Matched);

  // Beyond the radius (a tenth of the 0.2 mm field: 20 µm) no boundary is named.
  const pmsim::SectionBeckeProbe far = probe_at(*map, scene, {-45.0, 0.0});
  EXPECT_NEAR(far.radius_um, 20.0, 1e-9);
  EXPECT_FALSE(far.found);
  EXPECT_EQ(far.here.mineral, "high");
}

// sample.medium_index sets the mounting medium beyond the section's edge; an n = 1.60 grain's
// edge sends the line into the grain in a medium of 1.54 and out into the medium in 1.66 —
// probed from either side of the edge. The n_D read is the value set (the slab's medium).
TEST(SectionBeckeProbe, MediumIndexFlipsTheLineAtTheSectionEdge) {
  const pmsim::Crystal c = pmsim::Crystal::isotropic_constant("n160", 1.60);
  const auto map = one_grain_section(&c);
  for (const double nd : {1.54, 1.66}) {
    pmsim::Scene scene = section_scene();
    scene.sample.medium_index = nd;
    const pmsim::SectionBeckeProbe in = probe_at(*map, scene, {50.0, 0.0});
    ASSERT_TRUE(in.found) << nd;
    EXPECT_EQ(in.here.grain, 1);
    EXPECT_TRUE(in.there.is_medium());
    EXPECT_EQ(in.there.domain, SectionMap::kSlideDomain);  // beyond the section's extent
    EXPECT_NEAR(in.there.n, nd, 1e-12);
    EXPECT_NEAR(in.distance_um, 10.0, 1e-3);  // the edge x = 60 µm, straight east
    EXPECT_EQ(in.moves_into, nd < 1.60 ? BeckeMovesInto::Here : BeckeMovesInto::There) << nd;
    const pmsim::SectionBeckeProbe out = probe_at(*map, scene, {64.0, 20.0});
    ASSERT_TRUE(out.found) << nd;
    EXPECT_TRUE(out.here.is_medium());
    EXPECT_EQ(out.there.grain, 1);
    EXPECT_NEAR(out.distance_um, 4.0, 1e-3);
    EXPECT_EQ(out.moves_into, nd < 1.60 ? BeckeMovesInto::There : BeckeMovesInto::Here) << nd;
    std::printf("medium %.2f: %s\n", nd, pmsim::describe_section_becke_line(in).c_str());
  }
}

// The same at cleavage cracks of a real section (granite): a point 2 µm before the probe's line
// enters a crack finds the crack's wall within 2 µm, with the mounting medium beyond it, and the
// line flips with sample.medium_index between 1.40 and 1.80 (granite's minerals lie between).
TEST(SectionBeckeProbe, MediumIndexFlipsTheLineAtACrack) {
  pmsim::Scene scene = section_scene();
  scene.sample.section = "granite_hand_placed";
  const auto map = pmsim::load_scene_section(scene);
  const double h = pmsim::section_slab_options(scene).spacing_um;
  const std::vector<int> media = pmsim::section_slab_media(*map);
  const auto medium_at = [&](glm::dvec2 p_um) {
    return media[std::size_t(pmsim::section_slab_node(*map, 1e-3 * p_um, h).domain)];
  };
  // Along rows of the field: the first entry into a crack from 6 µm and more of one crystal medium.
  glm::dvec2 entry{0.0};
  bool have = false;
  for (double y = -80.0; y <= 80.0 && !have; y += 7.0) {
    int run = 0, previous = -1;
    for (double x = -80.0; x <= 80.0 && !have; x += 0.05) {
      const int m = medium_at({x, y});
      const bool crack = pmsim::section_slab_node(*map, 1e-3 * glm::dvec2(x, y), h).crack_family >= 0;
      if (crack && previous >= pmsim::kFirstFragment && run >= 120) {
        entry = {x, y};
        have = true;
      }
      run = m == previous ? run + 1 : 0;
      previous = m;
    }
  }
  ASSERT_TRUE(have) << "no crack in the granite's central 160 µm";
  const glm::dvec2 q = entry - glm::dvec2(2.0, 0.0);
  for (const double nd : {1.40, 1.80}) {
    scene.sample.medium_index = nd;
    const pmsim::SectionBeckeProbe p = probe_at(*map, scene, q);
    std::printf("crack entry at (%.2f, %.2f) µm: %s\n", entry.x, entry.y,
                pmsim::describe_section_becke_line(p).c_str());
    ASSERT_TRUE(p.found);
    EXPECT_FALSE(p.here.is_medium());
    EXPECT_TRUE(p.there.is_medium());
    EXPECT_EQ(p.there.domain, SectionMap::kMediumDomain);
    EXPECT_NEAR(p.there.n, nd, 1e-12);
    // The crack's wall is 2 µm away along the row (to the 0.05 µm scan step), nearer if the
    // crack crosses the row obliquely.
    EXPECT_LE(p.distance_um, 2.0 + 0.05);
    EXPECT_EQ(p.moves_into, nd < 1.5 ? BeckeMovesInto::Here : BeckeMovesInto::There);
  }
}

// A boundary of orientation alone: a simple twin of a uniaxial grain (n_ω 1.658, n_ε 1.486)
// whose twin individual has its optic axis turned 90° about the section normal, composition
// plane x = 0. For light vibrating along x the host (optic axis along x) offers n_ε, the twin
// (axis along y) n_ω: the line moves into the twin; with the polarizer at 90° the two swap.
TEST(SectionBeckeProbe, TwinBoundaryOfOneMineralFollowsTheOrientations) {
  const pmsim::Crystal c = pmsim::Crystal::uniaxial_constant("uniaxial", 1.658, 1.486);
  const glm::dmat3 host(glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0));  // Z along x
  const glm::dmat3 twin(glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0));   // Z along y
  auto map = std::make_shared<SectionMap>();
  map->width_mm = map->height_mm = 0.12;
  pmsim::SectionGrain g = grain(&c, {0.0, 0.0}, 0.12, host);
  g.twinned = true;
  g.twin_normal = {1.0, 0.0};  // individual 2 where (p − centre)·normal < 0: west of x = 0
  g.twin_orientation = g.zones[0].twin_orientation = twin;
  map->grains.push_back(g);
  map->finish();
  for (const double pol : {0.0, 90.0}) {
    const pmsim::Scene scene = section_scene(pol);
    const pmsim::SectionBeckeProbe p = probe_at(*map, scene, {-10.0, 0.0});
    ASSERT_TRUE(p.found);
    EXPECT_EQ(p.here.grain, 1);
    EXPECT_EQ(p.there.grain, 1);
    EXPECT_EQ(p.here.twin, 1);
    EXPECT_EQ(p.there.twin, 0);
    EXPECT_NEAR(p.distance_um, 10.0, 1e-3);
    EXPECT_NEAR(p.here.n, pol == 0.0 ? 1.658 : 1.486, 1e-12);
    EXPECT_NEAR(p.there.n, pol == 0.0 ? 1.486 : 1.658, 1e-12);
    EXPECT_EQ(p.moves_into, pol == 0.0 ? BeckeMovesInto::Here : BeckeMovesInto::There);
    const std::string text = pmsim::describe_section_becke_line(p);
    std::printf("polarizer %.0f: %s\n", pol, text.c_str());
    EXPECT_NE(text.find("uniaxial (grain 1, twin individual 2)"), std::string::npos) << text;
    EXPECT_NE(text.find("uniaxial (grain 1, twin individual 1)"), std::string::npos) << text;
  }
}

// A birefringent grain: calcite-like (n_ω 1.658, n_ε 1.486), optic axis Z in the x–z plane 30°
// above x. Light vibrating along x makes 30° with the optic axis: 1/n'² = cos²30°/n_ε² +
// sin²30°/n_ω² (the indicatrix's radius; Nesse 2012 §7); along y, ⟂ the axis: n_ω. Turning the
// polarizer 90° takes n' from the first to the second, and so does turning the stage 90° with the
// polarizer at 0° (the grain turns under the fixed polarizer). The values are those the slab
// tracer reads for the same medium (SpecimenScene::index), to the last bit.
TEST(SectionBeckeProbe, PolarizerTurnedNinetyDegreesChangesNPrimeAsTheIndicatrixSays) {
  const double no = 1.658, ne = 1.486, a = 30.0 * M_PI / 180.0;
  const pmsim::Crystal calcite = pmsim::Crystal::uniaxial_constant("calcite-like", no, ne);
  ASSERT_NEAR(calcite.principal_indices(kLambdaD).z, ne, 0.0);  // Z is the optic axis (ε)
  const glm::dvec3 Z{std::cos(a), 0.0, std::sin(a)}, X{-std::sin(a), 0.0, std::cos(a)}, Y{0.0, -1.0, 0.0};
  const auto map = one_grain_section(&calcite, glm::dmat3(X, Y, Z));
  const double n_x =
      1.0 / std::sqrt(std::cos(a) * std::cos(a) / (ne * ne) + std::sin(a) * std::sin(a) / (no * no));

  const pmsim::Scene p0 = section_scene(0.0), p90 = section_scene(90.0), s90 = section_scene(0.0, 90.0);
  // 10 µm inside the east edge (on the image's centre row: the stage turn leaves the centre).
  const pmsim::SectionBeckeProbe a0 = probe_at(*map, p0, {50.0, 0.0});
  const pmsim::SectionBeckeProbe a90 = probe_at(*map, p90, {50.0, 0.0});
  const pmsim::SectionBeckeProbe centre_s90 = pmsim::probe_section_becke_line(*map, s90, 0.5, 0.5, 80.0);
  std::printf("n' polarizer 0: %.6f (indicatrix %.6f); polarizer 90: %.6f (n_omega %.6f); stage 90: %.6f\n",
              a0.here.n, n_x, a90.here.n, no, centre_s90.here.n);
  // Constant indices and one formula: agreement to rounding (1e-12 of an index near 1.6).
  EXPECT_NEAR(a0.here.n, n_x, 1e-12);
  EXPECT_NEAR(a90.here.n, no, 1e-12);
  EXPECT_NEAR(centre_s90.here.n, no, 1e-12);
  // The change is this cut's birefringence for the two vibrations: n_ω − n' = 0.134 at 30°.
  EXPECT_NEAR(a90.here.n - a0.here.n, no - n_x, 1e-12);
  // In a medium of 1.60, between the two: the line moves out at 0° and in at 90° (calcite's
  // "twinkling" as the polarizer or the stage turns).
  pmsim::Scene m0 = p0, m90 = p90;
  m0.sample.medium_index = m90.sample.medium_index = 1.60;
  EXPECT_EQ(probe_at(*map, m0, {50.0, 0.0}).moves_into, BeckeMovesInto::There);
  EXPECT_EQ(probe_at(*map, m90, {50.0, 0.0}).moves_into, BeckeMovesInto::Here);

  // The slab the tracer gets holds the same medium: its index along the same vibration is equal.
  for (const pmsim::Scene* s : {&p0, &p90}) {
    const auto slab =
        pmsim::build_section_slab(map, pmsim::section_mounting_medium(*s), pmsim::section_slab_options(*s));
    const pmsim::SectionBeckeProbe r = probe_at(*map, *s, {50.0, 0.0});
    const int id = pmsim::section_slab_media(*map)[std::size_t(r.here.domain)];
    const glm::dvec3 v = pmsim::probe_point(*s, 0.75, 0.5).vibration;
    EXPECT_EQ(slab->index(id, kLambdaD, v), r.here.n);
    EXPECT_EQ(slab->liquid().n(kLambdaD), r.there.n);
  }
}

// What the probe claims is what the traced slab shows: an n = 1.60 grain's edge focused 20 µm
// up, in mounting media of 1.54 and 1.66. The brightest 2 µm band within 14 µm of the grain's
// edge (its trace on the slab's top; the wall leans by up to t·tan 25° = 14 µm over the slab)
// lies inside the grain when the probe says the line moves into it, outside when it says the
// medium — the measure tests/specimen_becke_probe_test.cpp applies to a fragment. (Focused 20 µm
// down the bands swap sides: measured +9 → −11 µm in 1.54 and −13 → +11 µm in 1.66.)
TEST(SectionBeckeProbe, TracedSlabShowsTheLineOnTheSideTheProbeNames) {
  const pmsim::Crystal c = pmsim::Crystal::isotropic_constant("n160", 1.60);
  const auto map = one_grain_section(&c);
  for (const double nd : {1.54, 1.66}) {
    pmsim::Scene scene = section_scene();
    scene.sample.medium_index = nd;
    scene.focus_um = 20.0;
    scene.render.single_wavelength_nm = kLambdaD;
    scene.render.spp = 32;
    const pmsim::SectionBeckeProbe p = probe_at(*map, scene, {50.0, 0.0});
    ASSERT_TRUE(p.found);
    const auto slab = pmsim::build_section_slab(map, pmsim::section_mounting_medium(scene),
                                                pmsim::section_slab_options(scene));
    const pmsim::PlaneLightOptions o = pmsim::plane_light_options(scene);
    const pmsim::RenderImage img = pmsim::render_plane_light(*slab, o);
    double sum[14] = {}, n[14] = {};
    for (int py = 0; py < o.height; ++py)
      for (int px = 0; px < o.width; ++px) {
        const double x = (px + 0.5 - 0.5 * o.width) * o.um_per_px,
                     y = (0.5 * o.height - (py + 0.5)) * o.um_per_px;
        const double d = 60.0 - std::max(std::abs(x), std::abs(y));  // + inside the grain
        if (!(std::abs(d) < 14.0)) continue;
        const int band = int(std::floor((d + 14.0) / 2.0));
        sum[band] += img.xyz[3 * (std::size_t(py) * o.width + px) + 1];
        n[band] += 1;
      }
    int peak = 0;
    for (int b = 1; b < 14; ++b)
      if (sum[b] / n[b] > sum[peak] / n[peak]) peak = b;
    const double centre = -13.0 + 2.0 * peak;
    std::printf("medium %.2f, focus +20 um: brightest band %.3f at %+.0f um from the edge; probe: %s\n", nd,
                sum[peak] / n[peak], centre, pmsim::describe_section_becke_line(p).c_str());
    EXPECT_EQ(centre > 0.0, p.moves_into == BeckeMovesInto::Here) << nd;
  }
}
