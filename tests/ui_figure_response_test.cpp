// The app on a conoscopic figure, and on a flat section view: once the view has converged its
// response is built (ui/render_feed.h), and a stage turn, a polar swing or an accessory pushed in
// is then composed from it — the image the app shows at the new setting is the view at that
// setting (against a fresh render), without a restart of the renderer (the composed images carry
// the feed's composed-image generations).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/microscope/view_geometry.h"
#include "core/render/progressive_renderer.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "ui/headless_driver.h"
#include "ui/script.h"

namespace pmsim::ui {
namespace {

constexpr std::uint64_t kComposedGeneration = 1ull << 62;  // RenderFeed::kGrainGeneration

bool composed(const App& app) { return (app.image().generation & kComposedGeneration) != 0; }

// Frames until the app shows a composed, current image of its scene, or the timeout.
bool until_composed(UiDriver& d, double timeout_s) {
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < timeout_s) {
    d.frame();
    if (composed(d.app()) && d.app().image_current() && d.app().converged()) return true;
  }
  return false;
}

// Mean CIEDE2000 over a figure's disc, or over a flat view one pixel in from its edge (a fresh
// render's edge pixels see no neighbour beyond it; tests/flat_response_test.cpp).
double mean_de(const Scene& scene, const RenderImage& a, const RenderImage& b) {
  const glm::dvec3 white = illuminant_white_xyz(scene.illuminant);
  const bool figure = scene.mode == ViewMode::Cono;
  double sum = 0.0;
  int n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const glm::dvec2 f = field_from_pixel(a.width, a.height, x + 0.5, y + 0.5);
      if (figure ? !bfp_lit(scene, std::hypot(f.x, f.y)) : (x == 0 || y == 0 || x + 1 == a.width || y + 1 == a.height))
        continue;
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * a.width + x);
      sum += ciede2000(xyz_to_lab({a.xyz[i], a.xyz[i + 1], a.xyz[i + 2]}, white),
                       xyz_to_lab({b.xyz[i], b.xyz[i + 1], b.xyz[i + 2]}, white));
      ++n;
    }
  return sum / std::max(1, n);
}

TEST(UiFigureResponse, StageTurnAndPolarSwingAreComposedFromTheFiguresResponse) {
  Scene s;
  s.mode = ViewMode::Cono;
  s.bertrand_in = true;
  s.objective = {50, 0.85};
  s.sample.type = SampleType::Plate;
  s.sample.mineral = "muscovite";  // biaxial negative, 2V ≈ 40°: isogyres that swing apart as the stage turns
  s.sample.thickness_um = 60;
  s.render.width = s.render.height = 64;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  ASSERT_TRUE(settle(*d, 120));
  // The probes (nine renders of a 64² figure) follow the converged render.
  ASSERT_TRUE(until_composed(*d, 120)) << "the figure's response was never built";
  // Pushing in the gypsum plate is composed too, from the figure's plan (figure_response.h).
  for (const std::string line : {"set stage_deg=30\n", "set analyzer_deg=75\n", "set compensator=gypsum\n"}) {
    ASSERT_TRUE(run_script(*d, parse_script(line, "t.pmsim"), "t.pmsim").ok) << line;
    ASSERT_TRUE(until_composed(*d, 10)) << line << ": not composed from the response";
    Scene fresh = d->app().scene();
    fresh.render.wavelengths = d->app().image().wavelengths;
    // Measured 0.09 for the first two (64²; 0.10 at 80² in tests/figure_response_test.cpp, where
    // a figure turned the wrong way is ≈ 40 away), 0.11 with the plate: 0.3 leaves a factor 3 and
    // is under one just-noticeable difference.
    const double de = mean_de(fresh, d->app().image(), ProgressiveRenderer::render(fresh));
    std::printf("%s -> mean ΔE00 %.3f against a fresh render\n", line.substr(4, line.size() - 5).c_str(), de);
    EXPECT_LT(de, 0.3) << line;
  }
}

TEST(UiFigureResponse, StageTurnOnAFlatSectionIsComposedFromItsProbes) {
  Scene s;  // the default granite between crossed polars, without relief: the flat section image
  s.sample.type = SampleType::Section;
  s.sample.section = "granite_hand_placed";
  s.optics.relief = false;
  s.render.width = s.render.height = 64;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  ASSERT_TRUE(settle(*d, 120));
  ASSERT_TRUE(until_composed(*d, 120)) << "the section's response was never built";
  // The gypsum plate pushed in: the canvas's units evaluated in the frame's train, no restart.
  for (const std::string line : {"set stage_deg=30\n", "set polarizer_deg=20\n", "set compensator=gypsum\n"}) {
    ASSERT_TRUE(run_script(*d, parse_script(line, "t.pmsim"), "t.pmsim").ok) << line;
    ASSERT_TRUE(until_composed(*d, 10)) << line << ": not composed from the response";
    Scene fresh = d->app().scene();
    fresh.render.wavelengths = d->app().image().wavelengths;
    Scene reference = fresh;  // 8 × 8 samples in every boundary pixel: the section's true pixels
    reference.render.spp = 64;
    const RenderImage truth = ProgressiveRenderer::render(reference);
    const double composed_de = mean_de(fresh, d->app().image(), truth);
    const double fresh_de = mean_de(fresh, ProgressiveRenderer::render(fresh), truth);
    std::printf("%s -> mean ΔE00 against a 64-sample reference: composed %.3f, fresh render %.3f\n",
                line.substr(4, line.size() - 5).c_str(), composed_de, fresh_de);
    // At 64² many of the granite's pixels hold a grain boundary, and a fresh render (2 × 2 samples
    // there) is itself 1.82 (stage 30°), 1.27 (then polarizer 20°) and 3.47 (then the gypsum
    // plate) from the reference; the composed image, the stage-0° canvas (3× finer than the view
    // at 64²) read turned by the cubic and box-filtered, measured 0.69, 0.48 and 1.25: no
    // further from the section than a fresh render. 1.25× the fresh render's distance bounds that; a canvas
    // turned the wrong way or off centre puts grains elsewhere (ΔE00 20–40).
    EXPECT_LT(composed_de, 1.25 * fresh_de) << line;
  }
}

}  // namespace
}  // namespace pmsim::ui
