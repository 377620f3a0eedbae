// EBSD maps as thin sections (issue 13, "Maps as sections"): the map's geometry on the section,
// the grains reconstructed by misorientation, the orientation clusters, the phase mapping and the
// non-indexed points, and what the microscope shows of them (extinction, isotropic phases, the
// c-axis convention of hexagonal phases, the conoscopic figure of a map grain). Every map is a
// file the test writes with core/ebsd/map_writer.h and reads back as a scene would.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/base/input_error.h"
#include "core/base/units.h"
#include "core/crystal/euler_angles.h"
#include "core/ebsd/ebsd_frames.h"
#include "core/ebsd/grain_reconstruction.h"
#include "core/ebsd/laue_rotations.h"
#include "core/ebsd/map_writer.h"
#include "core/io/scene_file.h"
#include "core/microscope/map_section.h"
#include "core/microscope/view_geometry.h"
#include "core/microscope/evaluation_plan.h"
#include "core/render/progressive_renderer.h"
#include "core/render/spectral_level.h"
#include "tests/ebsd_test_files.h"

using namespace pmsim;
using pmsim::ebsd_test::input_error_of;
using pmsim::ebsd_test::ScratchDir;

namespace {

EbsdPhase quartz_phase(int id = 1) {
  return {id, "Quartz", "SiO2", UnitCell{4.913, 4.913, 5.405, 90, 90, 120}, CrystalSystem::Trigonal, "-3m", "7", 154};
}
EbsdPhase garnet_phase(int id) {
  return {id, "Garnet", "", UnitCell{11.53, 11.53, 11.53, 90, 90, 90}, CrystalSystem::Cubic, "m-3m", "11", 230};
}

// A square Oxford map of columns × rows points, step_um apart, every point phase 1 at (φ1, Φ, φ2)°.
OrientationMap uniform_map(int columns, int rows, double step_um, std::vector<EbsdPhase> phases,
                           glm::dvec3 e_deg = {0, 0, 0}, EbsdVendor vendor = EbsdVendor::OxfordChannel5) {
  OrientationMap m;
  m.vendor = vendor;
  m.grid = MapGrid::Square;
  m.columns_odd = m.columns_even = columns;
  m.rows = rows;
  m.step_x_um = m.step_y_um = step_um;
  m.phases = std::move(phases);
  m.allocate_points();
  for (std::size_t i = 0; i < m.size(); ++i) {
    m.phase[i] = 1;
    m.phi1_rad[i] = static_cast<float>(radians(e_deg.x));
    m.Phi_rad[i] = static_cast<float>(radians(e_deg.y));
    m.phi2_rad[i] = static_cast<float>(radians(e_deg.z));
  }
  return m;
}

void set_euler_deg(OrientationMap& m, std::size_t i, double a, double b, double c) {
  m.phi1_rad[i] = static_cast<float>(radians(a));
  m.Phi_rad[i] = static_cast<float>(radians(b));
  m.phi2_rad[i] = static_cast<float>(radians(c));
}

Scene map_scene(const std::string& path, int size = 32) {
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = path;
  s.render.width = s.render.height = size;
  s.render.spp = 1;
  s.render.wavelengths = 16;
  s.objective.magnification = 10.0;
  return s;
}

double mean_luminance(const RenderImage& img) {
  double sum = 0.0;
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  for (std::size_t i = 0; i < n; ++i)
    sum += 0.2126 * img.rgb[3 * i] + 0.7152 * img.rgb[3 * i + 1] + 0.0722 * img.rgb[3 * i + 2];
  return sum / static_cast<double>(n);
}

double luminance_at(const RenderImage& img, int x, int y) {
  const std::size_t i = static_cast<std::size_t>(y) * img.width + x;
  return 0.2126 * img.rgb[3 * i] + 0.7152 * img.rgb[3 * i + 1] + 0.0722 * img.rgb[3 * i + 2];
}

}  // namespace

TEST(EbsdMapSection, GeometryOriginAtTheCentreNorthUpStepGivesTheScale) {
  ScratchDir dir;
  // 5 × 3 points 10 µm apart; point (column 4, row 0), the top right, is a second phase.
  OrientationMap m = uniform_map(5, 3, 10.0, {quartz_phase(1), garnet_phase(2)});
  m.phase[4] = 2;
  write_ctf(m, dir / "m.ctf");
  const auto s = load_map_section(dir / "m.ctf", {}, NonIndexed::Medium);
  ASSERT_TRUE(s->raster);
  // Extent: the points' extent (40 × 20 µm) plus one step, each point owning its step square.
  EXPECT_NEAR(s->width_mm, 0.050, 1e-12);
  EXPECT_NEAR(s->height_mm, 0.030, 1e-12);
  // The top-right point lies at (+20, +10) µm: x along the map's x, y against it (north up).
  const int d = s->domain_at({0.020, 0.010});
  EXPECT_EQ(s->mineral_of_domain(d), "almandine");
  EXPECT_EQ(s->mineral_of_domain(s->domain_at({-0.020, 0.010})), "quartz");
  EXPECT_EQ(s->mineral_of_domain(s->domain_at({0.020, -0.010})), "quartz");
  // The square the point owns reaches half a step (exclusive) in each direction; beyond the map
  // the slide.
  EXPECT_EQ(s->domain_at({0.0249, 0.0149}), d);
  EXPECT_EQ(s->domain_at({0.0251, 0.010}), SectionMap::kSlideDomain);
  EXPECT_EQ(s->domain_at({0.020, 0.0151}), SectionMap::kSlideDomain);
}

TEST(EbsdMapSection, HexagonalGridShiftsEverySecondRowByHalfAStep) {
  ScratchDir dir;
  OrientationMap m;
  m.vendor = EbsdVendor::EdaxTsl;
  m.grid = MapGrid::Hexagonal;
  m.columns_odd = 3;
  m.columns_even = 2;
  m.rows = 3;
  m.step_x_um = 10.0;
  m.step_y_um = 10.0 * std::sqrt(3.0) / 2.0;
  m.phases = {quartz_phase(1), garnet_phase(2)};
  m.allocate_points();
  for (std::size_t i = 0; i < m.size(); ++i) m.phase[i] = 1;
  m.phase[3] = 2;  // the second row's first point, at x = 5 µm
  write_ang(m, dir / "h.ang");
  const auto s = load_map_section(dir / "h.ang", {}, NonIndexed::Medium);
  // Points' extent 20 µm × √3·10 µm, centred: the second row's first point at (5 − 10, 0) µm.
  EXPECT_EQ(s->mineral_of_domain(s->domain_at({-0.005, 0.0})), "almandine");
  EXPECT_EQ(s->mineral_of_domain(s->domain_at({-0.0095, 0.0})), "almandine");  // 4.5 µm left of it
  EXPECT_EQ(s->mineral_of_domain(s->domain_at({-0.0105, 0.0})), "slide");      // beyond its brick
  EXPECT_EQ(s->mineral_of_domain(s->domain_at({-0.005, 0.006})), "quartz");    // the row above
}

TEST(EbsdMapSection, GrainsSplitAtFifteenDegreesAndJoinAtTwo) {
  ScratchDir dir;
  for (const double delta : {15.0, 2.0}) {
    // Left half (φ1 = 10°), right half turned `delta` about the section normal (φ1 = 10° + δ).
    OrientationMap m = uniform_map(8, 4, 5.0, {quartz_phase(1)}, {10, 30, 0});
    for (std::size_t i = 0; i < m.size(); ++i)
      if (i % 8 >= 4) set_euler_deg(m, i, 10 + delta, 30, 0);
    const std::string path = dir / ("g" + std::to_string(static_cast<int>(delta)) + ".ctf");
    write_ctf(m, path);
    const auto s = load_map_section(path, {}, NonIndexed::Medium);
    EXPECT_EQ(s->grains.size(), delta > 10 ? 2u : 1u) << delta;
    // Within a grain the halves differ by δ = 2° > the 0.5° cluster tolerance: two clusters.
    if (delta < 10) {
      EXPECT_EQ(s->grains[0].zones.size(), 2u);
      EXPECT_NE(s->domain_at({-0.005, 0.0}), s->domain_at({0.005, 0.0}));
      EXPECT_EQ(s->grain_label(s->domain_at({-0.005, 0.0})), s->grain_label(s->domain_at({0.005, 0.0})));
    }
  }
}

TEST(EbsdMapSection, MisorientationIsSymmetryAware) {
  // Quartz (-3m): a 120° turn about c is the same crystal, so two halves related by it are one
  // grain and one cluster; 60° about c is not a symmetry of -3m (a Dauphiné twin): two grains.
  ScratchDir dir;
  for (const double turn : {120.0, 60.0}) {
    OrientationMap m = uniform_map(6, 2, 5.0, {quartz_phase(1)}, {0, 0, 20});
    for (std::size_t i = 0; i < m.size(); ++i)
      if (i % 6 >= 3) set_euler_deg(m, i, 0, 0, 20 + turn);
    const std::string path = dir / ("s" + std::to_string(static_cast<int>(turn)) + ".ctf");
    write_ctf(m, path);
    const auto s = load_map_section(path, {}, NonIndexed::Medium);
    EXPECT_EQ(s->grains.size(), turn == 120.0 ? 1u : 2u) << turn;
  }
  EXPECT_EQ(laue_rotations("m-3m").size(), 24u);
  EXPECT_EQ(laue_rotations("6/mmm").size(), 12u);
  EXPECT_EQ(laue_rotations("-3m").size(), 6u);
  EXPECT_EQ(laue_rotations("2/m").size(), 2u);
}

TEST(EbsdMapSection, UnmappedPhaseIsAnInputErrorNamingItAndHowToMapIt) {
  ScratchDir dir;
  OrientationMap m = uniform_map(3, 3, 5.0, {quartz_phase(1), garnet_phase(2)});
  m.phases[1].name = "Unobtainium 7";
  m.phase[4] = 2;
  write_ctf(m, dir / "u.ctf");
  const InputError e = input_error_of([&] { load_map_section(dir / "u.ctf", {}, NonIndexed::Medium); });
  EXPECT_NE(std::string(e.what()).find("Unobtainium 7"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("sample.phases"), std::string::npos) << e.what();
  // Mapped explicitly (to a composition, to none, to isotropic) it loads.
  EXPECT_EQ(load_map_section(dir / "u.ctf", {{"Unobtainium 7", "olivine:Fo90"}}, NonIndexed::Medium)->grains.size(), 2u);
  const auto none = load_map_section(dir / "u.ctf", {{"Unobtainium 7", "none"}}, NonIndexed::Medium);
  EXPECT_EQ(none->domain_at({0, 0}), SectionMap::kMediumDomain);
  const auto iso = load_map_section(dir / "u.ctf", {{"unobtainium 7", "isotropic"}}, NonIndexed::Medium);
  EXPECT_EQ(iso->crystal_of_domain(iso->domain_at({0, 0})), nullptr);
  EXPECT_EQ(iso->mineral_of_domain(iso->domain_at({0, 0})), "isotropic");
}

TEST(EbsdMapSection, NonIndexedPointsShowTheMediumOrNothing) {
  ScratchDir dir;
  OrientationMap m = uniform_map(9, 9, 20.0, {quartz_phase(1)}, {90, 90, 0});
  for (std::size_t i = 0; i < m.size(); ++i) m.phase[i] = 0;  // all non-indexed
  write_ctf(m, dir / "n.ctf");
  Scene s = map_scene(dir / "n.ctf");
  s.analyzer_in = false;  // plane light: the medium is clear, an opaque point black
  s.objective.magnification = 100.0;  // a 0.2 mm field: the 0.18 mm map fills its centre
  const RenderImage a = ProgressiveRenderer::render(s);
  s.sample.nonindexed = NonIndexed::Black;
  const RenderImage b = ProgressiveRenderer::render(s);
  // Plane light through the mounting medium passes most of the lamp (> 0.5 of white); an opaque
  // point passes nothing (exactly 0: no unit is evaluated for it).
  EXPECT_GT(luminance_at(a, 16, 16), 0.5);
  EXPECT_EQ(luminance_at(b, 16, 16), 0.0);
}

TEST(EbsdMapSection, QuartzWithCAlongMapXIsExtinctAt0And90AndBrightestAt45) {
  ScratchDir dir;
  // Oxford Bunge (90°, 90°, 0°): the crystal's z (c) along the specimen's x, the map's x.
  write_ctf(uniform_map(24, 24, 50.0, {quartz_phase(1)}, {90, 90, 0}), dir / "q.ctf");
  Scene s = map_scene(dir / "q.ctf");
  s.objective.magnification = 40.0;  // a 0.5 mm field inside the 1.2 mm map
  std::vector<double> y;
  for (const double stage : {0.0, 22.5, 45.0, 67.5, 90.0}) {
    s.stage_deg = stage;
    y.push_back(mean_luminance(ProgressiveRenderer::render(s)));
  }
  // Extinct: the slow direction (c) parallel to the polarizer leaves the light polarised; only
  // the oblique rays of the NA 0.65 objective are not at extinction, and parallel-light
  // rendering (spp 1, orthoscopic) has none: below 1e-4 of white, 1/3000 of the 45° value.
  EXPECT_LT(y[0], 1e-4);
  EXPECT_LT(y[4], 1e-4);
  // Intensity ∝ sin²(2θ): 22.5° and 67.5° give half of 45°'s (±10 % for the spectral weighting of
  // first-order white, whose sin² term does not depend on θ).
  EXPECT_GT(y[2], 0.1) << "30 µm quartz, Γ ≈ 270 nm: first-order white";
  EXPECT_NEAR(y[1] / y[2], 0.5, 0.05);
  EXPECT_NEAR(y[3] / y[2], 0.5, 0.05);
}

TEST(EbsdMapSection, CubicPhaseIsBlackBetweenCrossedPolarsInEveryOrientation) {
  ScratchDir dir;
  // Garnet in six orientations, one per band of the map.
  OrientationMap m = uniform_map(12, 6, 50.0, {garnet_phase(1)});
  const double e[6][3] = {{0, 0, 0}, {30, 40, 50}, {90, 90, 0}, {123, 17, 300}, {200, 70, 10}, {350, 120, 45}};
  for (std::size_t i = 0; i < m.size(); ++i) {
    const int r = m.row_of(i);
    set_euler_deg(m, i, e[r][0], e[r][1], e[r][2]);
  }
  write_ctf(m, dir / "g.ctf");
  const auto sec = load_map_section(dir / "g.ctf", {}, NonIndexed::Medium);
  EXPECT_EQ(sec->grains.size(), 6u);
  for (const SectionGrain& g : sec->grains) EXPECT_EQ(g.zones.size(), 1u) << "isotropic: one domain per grain";
  Scene s = map_scene(dir / "g.ctf");
  s.objective.magnification = 40.0;
  for (const double stage : {0.0, 30.0, 45.0}) {
    s.stage_deg = stage;
    // Isotropic: no retardation, the analyser passes nothing (exactly 0 in parallel light; the
    // bound allows float rounding).
    EXPECT_LT(mean_luminance(ProgressiveRenderer::render(s)), 1e-6) << stage;
  }
}

TEST(EbsdMapSection, HexagonalCAxisConventionBothVendors) {
  ScratchDir dir;
  // The same Bunge angles (90°, 90°, 0°) put c along each vendor's Euler x: Oxford's is the
  // map's x (east), EDAX's the map's y (south) (core/ebsd/ebsd_frames.h).
  write_ctf(uniform_map(4, 4, 10.0, {quartz_phase(1)}, {90, 90, 0}), dir / "o.ctf");
  write_ang(uniform_map(4, 4, 10.0, {quartz_phase(1)}, {90, 90, 0}, EbsdVendor::EdaxTsl), dir / "e.ang");
  const auto o = load_map_section(dir / "o.ctf", {}, NonIndexed::Medium);
  const auto e = load_map_section(dir / "e.ang", {}, NonIndexed::Medium);
  ASSERT_TRUE(o->grains[0].lattice_to_section && e->grains[0].lattice_to_section);
  const glm::dvec3 co = (*o->grains[0].lattice_to_section)[2], ce = (*e->grains[0].lattice_to_section)[2];
  // Float angles (1e-7 rad) and the quaternion round trip: 1e-6.
  EXPECT_NEAR(std::abs(co.x), 1.0, 1e-6);
  EXPECT_NEAR(std::abs(ce.y), 1.0, 1e-6);
  // And the microscope sees it: at stage 45° the gypsum plate (slow direction NE–SW, 550 nm) adds
  // to a c (slow, quartz is positive) lying NE (Oxford: east turned 45° counter-clockwise) and
  // subtracts from one lying NW (EDAX: north–south turned 45°). In a 10 µm slab (Γ ≈ 90 nm):
  // 640 nm, second-order blue, against 460 nm, first-order orange.
  auto blue_minus_red = [&](const std::string& path) {
    Scene s = map_scene(path);
    s.objective.magnification = 100.0;  // the 40 µm map fills the 0.2 mm field's centre
    s.stage_deg = 45.0;
    s.sample.thickness_um = 10.0;
    s.compensator = Compensator::Gypsum;
    const RenderImage img = ProgressiveRenderer::render(s);
    const std::size_t i = static_cast<std::size_t>(16) * img.width + 16;
    return img.rgb[3 * i + 2] - img.rgb[3 * i];
  };
  EXPECT_GT(blue_minus_red(dir / "o.ctf"), 0.05);
  EXPECT_LT(blue_minus_red(dir / "e.ang"), -0.05);
}

TEST(EbsdMapSection, ConoscopicFigureIsOfTheGrainUnderTheCrosshair) {
  ScratchDir dir;
  // Left half: c normal to the section (Φ = 0); right half: c along the map's x.
  OrientationMap m = uniform_map(40, 20, 25.0, {quartz_phase(1)}, {0, 0, 0});
  for (std::size_t i = 0; i < m.size(); ++i)
    if (i % 40 >= 20) set_euler_deg(m, i, 90, 90, 0);
  write_ctf(m, dir / "c.ctf");
  auto figure = [&](Scene s) {
    s.mode = ViewMode::Cono;
    s.bertrand_in = true;
    s.objective.magnification = 40.0;
    s.objective.na = 0.65;
    s.render.width = s.render.height = 48;
    return ProgressiveRenderer::render(s);
  };
  Scene plate;
  plate.sample.mineral = "quartz";
  const auto diff = [](const RenderImage& a, const RenderImage& b) {
    double d = 0.0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) d = std::max(d, static_cast<double>(std::abs(a.rgb[i] - b.rgb[i])));
    return d;
  };
  Scene on_left = map_scene(dir / "c.ctf");
  on_left.stage.x_mm = -0.25;
  Scene on_right = on_left;
  on_right.stage.x_mm = 0.25;
  plate.sample.optic_axis = {0, 0, 1};
  const RenderImage axis_plate = figure(plate), left = figure(on_left);
  plate.sample.optic_axis = {1, 0, 0};
  const RenderImage flash_plate = figure(plate), right = figure(on_right);
  // The map grain's figure is the plate's of the same orientation and thickness (the same
  // evaluation; 1e-4 allows the float rounding of the map's angles), and not the other grain's.
  EXPECT_LT(diff(left, axis_plate), 1e-4);
  EXPECT_LT(diff(right, flash_plate), 1e-4);
  EXPECT_GT(diff(left, right), 0.1);
}

TEST(EbsdMapSection, SceneKeysRoundTripAndRefuseBadValues) {
  const nlohmann::json j = nlohmann::json::parse(
      R"({"sample": {"phases": {"Garnet 2": "almandine", "Epoxy": "none"}, "nonindexed": "black"},
          "render": {"native": "on"}})");
  const Scene s = scene_from_json(j, "f.json");
  EXPECT_EQ(s.sample.phases.at("Garnet 2"), "almandine");
  EXPECT_EQ(s.sample.phases.at("Epoxy"), "none");
  EXPECT_EQ(s.sample.nonindexed, NonIndexed::Black);
  EXPECT_TRUE(s.render.native);
  const Scene back = scene_from_json(scene_to_json(s), "saved");
  EXPECT_EQ(back.sample.phases, s.sample.phases);
  EXPECT_EQ(back.sample.nonindexed, NonIndexed::Black);
  EXPECT_TRUE(back.render.native);
  // Defaults are not written: every other scene saves as before.
  const nlohmann::json d = scene_to_json(Scene{});
  EXPECT_FALSE(d["sample"].contains("phases"));
  EXPECT_FALSE(d["sample"].contains("nonindexed"));
  EXPECT_FALSE(d["render"].contains("native"));
  Scene t;
  // A pair, not a structured binding: clang 14 (the sanitizer build) cannot capture a binding.
  for (const auto& bad : std::vector<std::pair<std::string, std::string>>{
           {"sample.nonindexed=grey", "sample.nonindexed"},
           {"render.native=maybe", "render.native"},
           {R"(sample.phases={"Garnet": 3})", "sample.phases"},
           {"sample.phases=[1]", "sample.phases"}}) {
    const InputError e = input_error_of([&] { apply_setting(t, bad.first); });
    EXPECT_EQ(e.key, bad.second) << bad.first;
  }
}

TEST(EbsdMapSection, InteractiveRestartRefusesAnUnmappedPhaseAndAcceptsItMapped) {
  ScratchDir dir;
  OrientationMap m = uniform_map(3, 3, 5.0, {quartz_phase(1), garnet_phase(2)});
  m.phases[1].name = "Unobtainium 7";
  m.phase[4] = 2;
  write_ctf(m, dir / "u.ctf");
  Scene s = map_scene(dir / "u.ctf");
  ProgressiveRenderer r;
  // The app's path: restart() refuses it as it refuses a bad key (the UI shows the message).
  const InputError e = input_error_of([&] { r.restart(s); });
  EXPECT_NE(std::string(e.what()).find("Unobtainium 7"), std::string::npos) << e.what();
  s.sample.phases = {{"Unobtainium 7", "isotropic"}};
  r.restart(s);
  EXPECT_TRUE(r.wait(60.0));
}

TEST(EbsdMapSection, UnduloseExtinctionSurvivesWithinOneGrain) {
  ScratchDir dir;
  // One quartz grain, c in the section turning steadily 0.2° per point from east (left) to 7.8°
  // (right): neighbours 0.2° apart, one grain; more than 0.5° across, several clusters.
  OrientationMap m = uniform_map(40, 10, 10.0, {quartz_phase(1)}, {90, 90, 0});
  for (std::size_t i = 0; i < m.size(); ++i) set_euler_deg(m, i, 90 + 0.2 * static_cast<double>(i % 40), 90, 0);
  write_ctf(m, dir / "b.ctf");
  const auto s = load_map_section(dir / "b.ctf", {}, NonIndexed::Medium);
  ASSERT_EQ(s->grains.size(), 1u);
  // Leader clusters of 0.5° over 7.8°: at least 7.8 / 1.0 (a cluster spans at most twice the
  // tolerance) and at most one per column.
  EXPECT_GE(s->grains[0].zones.size(), 8u);
  EXPECT_LE(s->grains[0].zones.size(), 40u);
  Scene sc = map_scene(dir / "b.ctf", 64);
  sc.objective.magnification = 40.0;  // 0.5 mm field: the 0.4 mm map spans pixels ≈ 6…57
  const RenderImage img = ProgressiveRenderer::render(sc);
  const double left = luminance_at(img, 8, 32), right = luminance_at(img, 55, 32);
  // Stage 0°: the left end is at extinction (c ∥ polarizer, within the 0.5° tolerance: leak
  // ≤ sin²(1°) = 3·10⁻⁴ of the 45° intensity), the right end 7.4–7.8° off it: sin²(2·7.5°) ≈ 0.067
  // of the 45° intensity (≈ 0.3, first-order white), so ≥ 0.01.
  EXPECT_LT(left, 1e-3);
  EXPECT_GT(right, 0.01);
  EXPECT_GT(right, 20.0 * left);
}

TEST(EbsdMapSection, GridNeighboursFourOnSquareSixOnHexagonal) {
  OrientationMap sq = uniform_map(5, 5, 1.0, {quartz_phase(1)});
  std::size_t nb[6];
  EXPECT_EQ(grid_neighbours(sq, 12, nb), 4);  // interior
  EXPECT_EQ(grid_neighbours(sq, 0, nb), 2);   // corner
  OrientationMap hx;
  hx.grid = MapGrid::Hexagonal;
  hx.columns_odd = 5;
  hx.columns_even = 4;
  hx.rows = 5;
  hx.step_x_um = 1.0;
  hx.step_y_um = std::sqrt(3.0) / 2.0;
  hx.allocate_points();
  // Row 2 (unshifted, starts at index 9), column 2: neighbours at distance one step exactly.
  const std::size_t i = hx.row_start(2) + 2;
  const int k = grid_neighbours(hx, i, nb);
  ASSERT_EQ(k, 6);
  for (int t = 0; t < k; ++t)
    EXPECT_NEAR(std::hypot(hx.x_um(nb[t]) - hx.x_um(i), hx.y_um(nb[t]) - hx.y_um(i)), 1.0, 1e-12) << t;
  // A shifted row's point (row 1, column 1) too.
  const std::size_t j = hx.row_start(1) + 1;
  ASSERT_EQ(grid_neighbours(hx, j, nb), 6);
  for (int t = 0; t < 6; ++t)
    EXPECT_NEAR(std::hypot(hx.x_um(nb[t]) - hx.x_um(j), hx.y_um(nb[t]) - hx.y_um(j)), 1.0, 1e-12) << t;
}

// The exact plates of a spectral level are prepared for the domains that exact units show, and
// only those (preparing all of a 10⁶-point map's 10⁴ domains at every band took most of its
// first image): the lookup gives bit-identical units to preparing every plate on demand.
TEST(EbsdMapSection, SpectralLevelPreparesExactPlatesOnlyForDomainsExactUnitsShow) {
  ScratchDir dir;
  // Left quarter quartz cut ⟂ c (optically active along its axis, with no linear retardation to
  // hide it: exact units), the rest quartz in 30 orientation clusters 2° apart with c in the
  // section (modal units).
  OrientationMap m = uniform_map(40, 10, 10.0, {quartz_phase(1)}, {0, 90, 0});
  for (std::size_t i = 0; i < m.size(); ++i) {
    const int col = static_cast<int>(i % 40);
    if (col < 10)
      set_euler_deg(m, i, 0, 0, 0);
    else
      set_euler_deg(m, i, 2.0 * (col - 10), 90, 0);
  }
  write_ctf(m, dir / "e.ctf");
  Scene sc = map_scene(dir / "e.ctf", 64);
  sc.objective.magnification = 40.0;  // 0.5 mm field: the whole 0.4 mm map
  const auto plan = compile_evaluation_plan(sc);
  ASSERT_TRUE(plan);
  ASSERT_TRUE(plan->any_exact());  // the basal quartz
  const SpectralLevel L = make_spectral_level(*plan, 16);
  std::set<int> exact_domains, modal_domains;
  for (std::size_t u = 0; u < plan->units().size(); ++u)
    (plan->needs_exact(static_cast<int>(u)) ? exact_domains : modal_domains).insert(plan->units()[u].domain);
  ASSERT_FALSE(modal_domains.empty());
  // One slot per domain an exact unit shows, none for the others.
  ASSERT_EQ(L.prepared.size(), 16u);
  EXPECT_EQ(L.prepared[0].size(), exact_domains.size());
  for (int d = 0; d < static_cast<int>(plan->domains().size()); ++d)
    EXPECT_EQ(L.plate(0, d) != nullptr, exact_domains.count(d) > 0 && plan->domains()[d].crystal) << "domain " << d;
  // Exact: the same prepare_plate values, looked up or prepared on demand.
  SpectralLevel on_demand = L;
  on_demand.prepared.clear();
  on_demand.prepared_slot.clear();
  for (std::size_t u = 0; u < plan->units().size(); ++u) {
    const glm::dvec3 a = evaluate_unit(*plan, L, static_cast<int>(u));
    const glm::dvec3 b = evaluate_unit(*plan, on_demand, static_cast<int>(u));
    EXPECT_EQ(a, b) << "unit " << u;
  }
}
