// A flat orthoscopic section view composed from its nine probes (core/specimen/figure_response.h,
// flat_response_applies): the probes cover a canvas that holds the view at every stage angle, a
// frame reads the view's pixels turned out of it. Against fresh renders at the same spectral level,
// on a three-grain section without relief (64², the CI budget): at stage 0° the probes' linear
// combination is the render itself; at a turned stage a pixel's sub-samples read the canvas's
// nearest labels, and only those next to a grain boundary can read across it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "core/render/progressive_renderer.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "core/specimen/figure_response.h"
#include "tests/section_file_fixture.h"

namespace {

using namespace pmsim;

// Three grains across a 0.2 mm field: quartz with its axis in the section at 20° and at 80°, and
// biotite (absorbing: evaluated exactly, the probes' band-by-band path).
Scene section_scene() {
  using section_test::grain_with_axis_in_plane;
  const std::string p = section_test::write_section(
      "three.json",
      {grain_with_axis_in_plane("quartz", -0.05, 0.03, 0.12, 20.0), grain_with_axis_in_plane("quartz", 0.06, 0.02, 0.1, 80.0),
       {{"mineral", "biotite"}, {"centre_mm", {0.0, -0.07}}, {"size_mm", 0.09}, {"euler_deg", {68.0, 128.0, 65.0}}}},
      0.4);
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = p;
  s.optics.relief = false;
  s.objective.magnification = 100.0;
  s.render.width = s.render.height = 64;
  return s;
}

Scene at(Scene s, double stage_deg, double pol_deg, bool analyzer_in, double ana_deg, int wavelengths) {
  s.stage_deg = stage_deg;
  s.polarizer_deg = pol_deg;
  s.analyzer_in = analyzer_in;
  s.analyzer_deg = ana_deg;
  s.render.wavelengths = wavelengths;
  return s;
}

struct Difference {
  double mean_de = 0.0, max_abs_xyz = 0.0;
};

// Over every pixel, the edges' included (a fresh render's edge pixel looks up its neighbour beyond
// the edge in the section, as the canvas has it).
Difference difference(const RenderImage& a, const RenderImage& b) {
  const glm::dvec3 white = illuminant_white_xyz(Illuminant::D65);
  Difference d;
  int count = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * a.width + x);
      for (int c = 0; c < 3; ++c) d.max_abs_xyz = std::max(d.max_abs_xyz, std::abs(double(a.xyz[i + c]) - b.xyz[i + c]));
      d.mean_de += ciede2000(xyz_to_lab(glm::dvec3(a.xyz[i], a.xyz[i + 1], a.xyz[i + 2]), white),
                             xyz_to_lab(glm::dvec3(b.xyz[i], b.xyz[i + 1], b.xyz[i + 2]), white));
      ++count;
    }
  d.mean_de /= std::max(1, count);
  return d;
}

TEST(FlatResponse, AppliesToSectionsInTheOrthoscope) {
  Scene s = section_scene();
  EXPECT_TRUE(flat_response_applies(s));
  s.compensator = Compensator::Gypsum;  // frames with an accessory evaluate the canvas's plan
  EXPECT_TRUE(flat_response_applies(s));
  s.compensator = Compensator::None;
  s.sample.type = SampleType::Wedge;  // its thickness runs across the rendered field
  EXPECT_FALSE(flat_response_applies(s));
  s.sample.type = SampleType::Section;
  s.bertrand_in = true;  // the parallel-light spot
  EXPECT_FALSE(flat_response_applies(s));
  s.bertrand_in = false;
  s.render.width = s.render.height = 1024;  // canvas 1454²: 228 MB of probes
  EXPECT_TRUE(flat_response_applies(s));
  s.render.width = s.render.height = 2048;  // canvas 2902²: 0.9 GB; rendered per setting instead
  EXPECT_FALSE(flat_response_applies(s));
}

// A render of `s` at k times its pixels, box-filtered back to its pixels: what a k-times-finer
// canvas read at stage 0° holds for each view pixel.
RenderImage box_filtered_render(Scene s, int k) {
  const int w = s.render.width, h = s.render.height;
  s.render.width *= k;
  s.render.height *= k;
  const RenderImage fine = ProgressiveRenderer::render(s);
  RenderImage img;
  img.width = w;
  img.height = h;
  img.xyz.assign(3 * static_cast<std::size_t>(w) * h, 0.0f);
  for (int y = 0; y < h * k; ++y)
    for (int x = 0; x < w * k; ++x)
      for (int c = 0; c < 3; ++c)
        img.xyz[3 * (static_cast<std::size_t>(y / k) * w + x / k) + c] +=
            fine.xyz[3 * (static_cast<std::size_t>(y) * w * k + x) + c] / static_cast<float>(k * k);
  return img;
}

TEST(FlatResponse, ComposedAtStageZeroIsTheFreshSectionAtAnyPolars) {
  const Scene scene = section_scene();
  const auto r = render_figure_response(scene);
  ASSERT_TRUE(r.has_value());
  EXPECT_TRUE(r->flat);
  // A 64² view's canvas (96 view pixels) is rendered 3× finer (kFlatCanvasMinSide 256).
  EXPECT_EQ(r->scale, 3);
  EXPECT_EQ(r->width, 96 * 3);  // the canvas holds the view's circumscribed circle
  EXPECT_EQ(r->image_width, 64);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(0.0, 180.0);
  for (int k = 0; k < 3; ++k) {
    const bool analyzer_in = k != 2;
    const Scene s = at(scene, 0.0, angle(rng), analyzer_in, angle(rng), r->wavelengths);
    const Difference d = difference(compose_figure(*r, instrument_settings(s)), box_filtered_render(s, r->scale));
    std::printf("polars %.1f/%.1f%s: max |ΔXYZ| %.2e\n", s.polarizer_deg, s.analyzer_deg,
                analyzer_in ? "" : " (analyzer out)", d.max_abs_xyz);
    // At stage 0° the canvas cells a view pixel reads are the fine render's pixels, and the probes
    // combine in float with weights ≤ 1.5 from values ≤ 1, averaged over 9: a few float ulps of
    // XYZ ≈ 1; 1e-5 leaves ~10² of margin, and a wrong weight, a shifted canvas or a cell read
    // from the neighbouring pixel moves XYZ by 10⁻² or more.
    EXPECT_LT(d.max_abs_xyz, 1e-5);
  }
}

TEST(FlatResponse, ComposedAtATurnedStageIsTheFreshSectionBarBoundarySubSamples) {
  const Scene scene = section_scene();
  const auto r = render_figure_response(scene);
  ASSERT_TRUE(r.has_value());
  for (const double stage : {30.0, 117.0}) {
    const Scene s = at(scene, stage, 10.0, true, 100.0, r->wavelengths);
    const RenderImage composed = compose_figure(*r, instrument_settings(s));
    const Difference d = difference(composed, ProgressiveRenderer::render(s));
    const Difference w = difference(composed, ProgressiveRenderer::render(at(scene, -stage, 10.0, true, 100.0, r->wavelengths)));
    std::printf("stage %.0f°: mean ΔE00 %.3f; against the section turned the wrong way %.3f\n", stage, d.mean_de,
                w.mean_de);
    // Measured 0.109–0.113 here with the 3×-finer canvas (36 sub-samples a view pixel against the
    // fresh render's 4; the cubic read of canvas colours gave 0.12–0.14; docs/response.md). Issue
    // 21's bound, 1.0, leaves 9× of margin; the section turned the wrong way (its grains
    // elsewhere) is 180–400× further, so a sign or centre error cannot pass.
    EXPECT_LT(d.mean_de, 1.0);
    EXPECT_GT(w.mean_de, 10.0 * d.mean_de);
  }
}

Scene with_accessory(Scene s, Compensator c, double position) {
  s.compensator = c;
  s.compensator_position = position;
  return s;
}

// With an accessory in the slot a frame evaluates the canvas's units in its own train turned into
// the specimen's frame (figure_response.h): at stage 0° the train is the fresh render's own, so
// the developed canvas is its pixels.
TEST(FlatResponse, AnAccessoryAtStageZeroIsTheFreshSection) {
  const Scene scene = section_scene();
  const auto r = render_figure_response(scene);
  ASSERT_TRUE(r.has_value());
  ASSERT_TRUE(r->plan && r->level);
  struct Case {
    Compensator c;
    double position, pol, ana;
    bool analyzer_in;
  };
  const Case cases[] = {{Compensator::Gypsum, 0.0, 0.0, 90.0, true},
                        {Compensator::QuartzWedge, 0.6, 23.0, 131.0, true},
                        {Compensator::Mica, 0.0, 70.0, 0.0, false}};
  for (const Case& c : cases) {
    const Scene s = with_accessory(at(scene, 0.0, c.pol, c.analyzer_in, c.ana, r->wavelengths), c.c, c.position);
    const Difference d = difference(compose_figure(*r, instrument_settings(s)), box_filtered_render(s, r->scale));
    std::printf("accessory %d at %.1f, polars %.0f/%.0f: max |ΔXYZ| %.2e\n", static_cast<int>(c.c), c.position, c.pol,
                c.ana, d.max_abs_xyz);
    // The same units in the same train, summed in float by the same weights as the render's
    // pixels and box-filtered alike: float rounding of XYZ ≤ 1 (as the probes' test above, 1e-5
    // leaves ~10² of margin); the wrong accessory, position or polar moves XYZ by 10⁻² or more.
    EXPECT_LT(d.max_abs_xyz, 1e-5);
  }
}

// Turned, the slot and the polars must turn by −θ in the specimen's frame: the gypsum plate adds
// to a grain whose slow direction lies along the slot's and subtracts across it, so a slot turned
// the wrong way (at 45° + θ) gives the grains the complementary colours.
TEST(FlatResponse, AnAccessoryAtATurnedStageIsTheFreshSectionBarBoundarySubSamples) {
  const Scene scene = section_scene();
  const auto r = render_figure_response(scene);
  ASSERT_TRUE(r.has_value());
  for (const auto& [stage, c, position] : {std::tuple{30.0, Compensator::Gypsum, 0.0},
                                          std::tuple{117.0, Compensator::QuartzWedge, 0.35}}) {
    const Scene s = with_accessory(at(scene, stage, 10.0, true, 100.0, r->wavelengths), c, position);
    const RenderImage composed = compose_figure(*r, instrument_settings(s));
    const Difference d = difference(composed, ProgressiveRenderer::render(s));
    std::printf("stage %.0f°, accessory %d: mean ΔE00 %.3f\n", stage, static_cast<int>(c), d.mean_de);
    // Measured 0.133 (gypsum, 30°) and 0.125 (wedge, 117°), as without an accessory (0.11
    // above): the boundary pixels' sampling, the units themselves are exact in the turned train
    // (render_units_in_trains_test: ≤ 1.4e-14). Issue 21's bound 1.0 leaves 7× of margin; the slot turned the wrong way makes grains' additions
    // subtractions (0.3–0.9 in XYZ over whole grains there).
    EXPECT_LT(d.mean_de, 1.0);
  }
}

}  // namespace

// A frame samples each view pixel as a fresh render does (n × n sub-samples), each sub-sample
// showing the unit of the canvas label nearest its turned position (figure_response.h). So a
// pixel whose neighbourhood lies inside one grain is that grain's unit exactly — no blur inside a
// grain —, and only pixels on a boundary can differ from a fresh render, by the sub-samples whose
// nearest label lies across it. At 192² the canvas (276 px) is at the view's pitch (k = 1), the
// app's case.
TEST(FlatResponse, ATurnedFrameDiffersFromAFreshRenderOnlyOnGrainBoundaries) {
  Scene scene = section_scene();
  scene.render.width = scene.render.height = 192;
  scene.objective.magnification = 40.0;
  const auto r = render_figure_response(scene);
  ASSERT_TRUE(r.has_value());
  ASSERT_EQ(r->scale, 1);
  for (const double stage : {30.0, 117.0}) {
    const Scene s = with_accessory(at(scene, stage, 0.0, true, 90.0, r->wavelengths), Compensator::Gypsum, 0.0);
    const RenderImage composed = compose_figure(*r, instrument_settings(s));
    const RenderImage fresh = ProgressiveRenderer::render(s);
    const int W = fresh.width, H = fresh.height;
    auto at_xyz = [&](const RenderImage& img, int x, int y) {
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * W + x);
      return glm::dvec3(img.xyz[i], img.xyz[i + 1], img.xyz[i + 2]);
    };
    int differ = 0, differ_inside = 0, boundary = 0;
    for (int y = 1; y + 1 < H; ++y)
      for (int x = 1; x + 1 < W; ++x) {
        // Inside a grain: the fresh render's 3 × 3 neighbourhood is one colour (a sub-sample of a
        // turned pixel lies within 0.71 px of its centre, its nearest label within 0.12 px more).
        bool inside = true;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            inside = inside && glm::length(at_xyz(fresh, x + dx, y + dy) - at_xyz(fresh, x, y)) < 1e-6;
        const bool d = glm::length(at_xyz(composed, x, y) - at_xyz(fresh, x, y)) > 1e-5;
        boundary += !inside;
        differ += d;
        differ_inside += d && inside;
      }
    const Difference de = difference(composed, fresh);
    std::printf("stage %.0f°, gypsum: %d of %d boundary pixels differ from the fresh render, %d inside grains; mean "
                "ΔE00 %.3f\n",
                stage, differ, boundary, differ_inside, de.mean_de);
    // Float rounding of one unit's XYZ (≤ 1) is ~1e-7; 1e-5 is a colour no eye sees. A canvas
    // shifted or turned by as little as a label cell (1/6 px) moves boundary pixels only, but
    // one read by the cubic blurred every pixel next to a boundary (a third of the boundary band
    // inside the 3 × 3 test).
    EXPECT_EQ(differ_inside, 0);
    // Measured 17–18 % of the boundary pixels differing (in those one sub-sample of four reads
    // its label across the boundary); labels away from where the fresh render samples, by half a
    // sub-sample's spacing, make most of them differ.
    EXPECT_LT(differ, boundary / 2);
    // Measured 0.19 over the whole image (the cubic read gave 0.7–2.0 at 512² on the granites,
    // docs/response.md); issue 21's bound 1.0.
    EXPECT_LT(de.mean_de, 1.0);
  }
}
