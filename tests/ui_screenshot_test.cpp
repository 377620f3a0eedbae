// Off-screen screenshots of the whole window, checked by their pixels: the field sits where the
// layout says, and it shows what the instrument shows for a few textbook states.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/image_file.h"
#include "core/io/scene_file.h"
#include "ui/headless_driver.h"
#include "ui/script.h"

namespace pmsim::ui {
namespace {

struct Rgb {
  double r = 0, g = 0, b = 0;
  double max() const { return std::max({r, g, b}); }
  double min() const { return std::min({r, g, b}); }
  double mean() const { return (r + g + b) / 3; }
};

// Mean colour of a (2h+1)² box of window pixels around (x, y).
Rgb box(const WindowPixels& px, float x, float y, int h = 3) {
  Rgb sum;
  int n = 0;
  for (int dy = -h; dy <= h; ++dy)
    for (int dx = -h; dx <= h; ++dx) {
      const int xi = static_cast<int>(x) + dx, yi = static_cast<int>(y) + dy;
      const std::uint8_t* p = &px.rgb[(static_cast<size_t>(yi) * px.width + xi) * 3];
      sum.r += p[0], sum.g += p[1], sum.b += p[2];
      ++n;
    }
  return {sum.r / n, sum.g / n, sum.b / n};
}

// Window pixels at a point of the field given as offsets from its centre in units of its radius
// (+x east, +y north).
Rgb field_at(const WindowPixels& px, const Layout& l, double east, double north, int h = 3) {
  const double r = l.field_radius();
  return box(px, static_cast<float>(l.field.cx() + east * r), static_cast<float>(l.field.cy() - north * r),
             h);
}

// Small images keep the suite fast; the layout scales them up to the field.
Scene test_scene() {
  Scene s;
  s.render.width = s.render.height = 96;
  return s;
}

WindowPixels shot(const Scene& scene, Layout* layout = nullptr) {
  std::string log;
  auto d = HeadlessDriver::create(scene, 1280, 800, log);
  if (!d) ADD_FAILURE() << log;
  if (!d) return {};
  EXPECT_TRUE(settle(*d, 120)) << "the image did not converge";
  if (layout) *layout = d->app().layout();
  return d->read_pixels();
}

TEST(UiScreenshot, FieldSitsWhereTheLayoutSaysAndCrossedPolarsWithoutSampleAreBlack) {
  Scene s = test_scene();
  s.sample_in = false;
  Layout l;
  const WindowPixels px = shot(s, &l);
  ASSERT_EQ(px.width, 1280);
  ASSERT_EQ(px.height, 800);
  // The field is large at 1280x800: more than 70 % of the height.
  EXPECT_GT(l.field.h, 0.7f * 800);
  // Crossed polars, empty stage: no light. Off the crosshair lines, at several radii; 8 of 255
  // allows the renderer's noise and texture filtering but no visible light.
  for (double r : {0.1, 0.5, 0.85})
    for (double a : {0.4, 2.0, 3.6, 5.0}) {
      const Rgb c = field_at(px, l, r * std::cos(a), r * std::sin(a));
      EXPECT_LT(c.max(), 8.0) << "r " << r << " angle " << a;
    }
  // Outside the circular field stop but inside its square: the panel's grey, not the image.
  const Rgb corner = box(px, l.field.x + 6, l.field.y + 6);
  EXPECT_NEAR(corner.mean(), 0.22 * 255, 6.0);
  // Left of the field: the controls panel, right of it: the teaching panel (both dark UI).
  EXPECT_LT(box(px, l.controls.x + l.controls.w - 4, 790, 1).mean(), 40);
}

TEST(UiScreenshot, AnalyzerOutGivesAWhiteField) {
  Scene s = test_scene();
  s.sample_in = false;
  s.analyzer_in = false;
  Layout l;
  const WindowPixels px = shot(s, &l);
  // Exposure convention (issue 3): an empty stage with the analyzer out is Y = 1, D65 white →
  // sRGB (255,255,255); 245 leaves room for filtering at the edges of boxes, not for a tint.
  for (double r : {0.0 + 0.05, 0.5, 0.85}) {
    const Rgb c = field_at(px, l, r * 0.6, r * 0.8);
    EXPECT_GT(c.min(), 245.0) << "r " << r;
  }
  const Rgb corner = box(px, l.field.x + 6, l.field.y + l.field.h - 7);
  EXPECT_NEAR(corner.mean(), 0.22 * 255, 6.0);
}

TEST(UiScreenshot, QuartzPlate30umAt45DegreesShowsFirstOrderWhite) {
  // Quartz 30 µm cut parallel to c: Γ = d·(ne − no) ≈ 30 µm × 0.0091 ≈ 273 nm. On the
  // Michel-Lévy chart that is first-order white (between the grey of ~200 nm and the yellow of
  // ~330 nm): bright and nearly neutral. Bands: every channel above 170 (Y of sin²(πΓ/λ) weighted
  // by D65 at 273 nm is ≈ 0.7, i.e. sRGB ≈ 220) and a spread below 50 (the chart's first-order
  // white is a slightly yellowish white, not a saturated colour).
  Scene s = test_scene();
  s.sample.mineral = "quartz";
  s.sample.thickness_um = 30;
  s.sample.optic_axis = {1, 0, 0};
  s.stage_deg = 45;
  Layout l;
  const WindowPixels px = shot(s, &l);
  for (double r : {0.2, 0.6}) {
    const Rgb c = field_at(px, l, r * 0.8, r * 0.6);
    EXPECT_GT(c.min(), 170.0) << "r " << r;
    EXPECT_LT(c.max() - c.min(), 50.0) << "r " << r;
  }
  // At stage 0° its vibration directions are parallel to the polars: extinction.
  s.stage_deg = 0;
  const WindowPixels dark = shot(s, &l);
  EXPECT_LT(field_at(dark, l, 0.3, 0.4).max(), 10.0);
}

TEST(UiScreenshot, ConoscopicCalciteShowsADarkCrossAlongThePolars) {
  // Calcite cut ⟂ c, conoscopic: the uniaxial optic-axis figure, isogyres along the polarizer
  // (E–W) and analyzer (N–S) directions, isochromes in between.
  Scene s = test_scene();
  s.mode = ViewMode::Cono;
  s.bertrand_in = true;
  s.sample.mineral = "calcite";
  s.sample.optic_axis = {0, 0, 1};
  s.objective = {50, 0.85};
  Layout l;
  const WindowPixels px = shot(s, &l);
  // 4 px beside the crosshair lines (which are drawn on top of the image), at radii 0.2–0.7.
  const double off = 4.0 / l.field_radius();
  double arms = 0, quadrants = 0;
  int n = 0;
  for (double r : {0.2, 0.35, 0.5, 0.7}) {
    for (const auto& [e, nn] : {std::pair{r, off}, {-r, -off}, {off, r}, {-off, -r}}) {
      const Rgb c = field_at(px, l, e, nn, 1);
      EXPECT_LT(c.max(), 40.0) << "isogyre at " << e << "," << nn;  // dark, not merely dimmer
      arms += c.mean();
    }
    for (const auto& [e, nn] : {std::pair{r, r}, {-r, r}, {r, -r}, {-r, -r}}) {
      quadrants += field_at(px, l, e * 0.7071, nn * 0.7071, 1).mean();
      ++n;
    }
  }
  // Between the arms the field is lit: the mean over the diagonals is far above the arms'.
  EXPECT_GT(quadrants / n, 4 * (arms / n) + 30);
  // Outside the back focal plane disk and the field stop: the panel's grey.
  EXPECT_NEAR(box(px, l.field.x + 6, l.field.y + 6).mean(), 0.22 * 255, 6.0);
}

// Every window pixel inside the field stop at r ≤ 0.8 off the crosshair (grey level, mean of R, G, B).
std::vector<double> field_pixels(const WindowPixels& px, const Layout& l) {
  std::vector<double> v;
  const double r = 0.8 * l.field_radius();
  for (int y = static_cast<int>(l.field.cy() - r); y <= static_cast<int>(l.field.cy() + r); ++y)
    for (int x = static_cast<int>(l.field.cx() - r); x <= static_cast<int>(l.field.cx() + r); ++x)
      if (std::hypot(x - l.field.cx(), y - l.field.cy()) <= r && std::abs(x - l.field.cx()) > 3 &&
          std::abs(y - l.field.cy()) > 3) {  // off the crosshair lines, drawn over the image
        const std::uint8_t* p = &px.rgb[(static_cast<size_t>(y) * px.width + x) * 3];
        v.push_back((p[0] + p[1] + p[2]) / 3.0);
      }
  return v;
}

TEST(UiScreenshot, GrainMountFromTheSampleTypeChangesWithTheFineFocus) {
  // A plate on the stage in plane light, then the sample type switched to a grain mount of
  // almandine (n ≈ 1.83) in a liquid of 1.54: the image is the specimen renderer's — fragments
  // with dark outlines (light refracted out of the objective's aperture) instead of the plate's
  // even field — and it changes when the fine focus moves (the Becke line and the outlines shift).
  Scene s = test_scene();
  s.analyzer_in = false;
  s.objective.magnification = 40;  // 0.5 mm field: fragments of 30–300 µm fill it at ~5 µm a pixel
  s.objective.na = 0.65;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  ASSERT_TRUE(settle(*d, 120));
  const Layout l = d->app().layout();
  const std::vector<double> plate = field_pixels(d->read_pixels(), l);

  ASSERT_TRUE(d->app().set("sample.type=grains"));
  ASSERT_TRUE(d->app().set("sample.mineral=almandine"));
  ASSERT_TRUE(d->app().set("sample.medium_index=1.54"));
  ASSERT_TRUE(settle(*d, 120)) << "the grain mount did not converge";
  EXPECT_EQ(d->app().image().model_report.rfind("grain mount", 0), 0u) << d->app().image().model_report;
  const std::vector<double> focus0 = field_pixels(d->read_pixels(), l);
  // The default plate in plane light is an even bright field; the mount has dark outlines: count
  // the pixels below 200 of 255.
  const auto dark_fraction = [](const std::vector<double>& v) {
    return static_cast<double>(std::count_if(v.begin(), v.end(), [](double g) { return g < 200.0; })) /
           static_cast<double>(v.size());
  };
  const double plate_dark = dark_fraction(plate), mount_dark = dark_fraction(focus0);
  // Measured 0.0010 (the scale bar drawn over the plate) and 0.0072 (almandine's rims at 40×,
  // forward-traced: at NA 0.65 most light bent at a rim is still collected, so the dark rims are
  // thin rings; the backward sampler's 0.09 at < 128 was mostly its heavy-tailed noise, dark
  // where no rare lit ray had come yet): the bounds sit a factor 2–3 from each.
  EXPECT_LT(plate_dark, 0.0025);
  EXPECT_GT(mount_dark, 0.0035);

  // Fine focus up 15 µm by the keys (Shift+Up, 1 µm a press).
  for (int k = 0; k < 15; ++k) d->app().perform(Action::FocusUp);
  EXPECT_DOUBLE_EQ(d->app().scene().focus_um, 15.0);
  ASSERT_TRUE(settle(*d, 120));
  const std::vector<double> up = field_pixels(d->read_pixels(), l);
  // Where the focus acts: the Becke line and the outline move, the liquid between fragments stays
  // the empty field's white. Mean change at pixels that are dark (< 200 of 255) in either image,
  // against the mean change where both are near white (> 240): the ratio separates refraction at
  // the boundaries from a change of the sampling noise, which would touch every pixel alike.
  double edge_sum = 0, flat_sum = 0;
  std::size_t edge_n = 0, flat_n = 0;
  for (std::size_t k = 0; k < up.size(); ++k) {
    const double dk = std::abs(focus0[k] - up[k]);
    if (focus0[k] < 200 || up[k] < 200) edge_sum += dk, ++edge_n;
    if (focus0[k] > 240 && up[k] > 240) flat_sum += dk, ++flat_n;
  }
  ASSERT_GT(edge_n, 0u);
  ASSERT_GT(flat_n, 0u);
  const double edge = edge_sum / edge_n, flat = flat_sum / flat_n;
  std::printf("grain mount: mean change at outlines %.2f, in the liquid %.3f of 255 (dark: plate %.4f, mount %.4f)\n",
              edge, flat, plate_dark, mount_dark);
  // Measured 6.3 against 0.02 of 255: a ratio of 20 and a change of 2 grey levels are far inside
  // both, and neither would be met by a re-drawn noise pattern (ratio ≈ 1) or by an unchanged image.
  EXPECT_GT(edge, 20.0 * flat);
  EXPECT_GT(edge, 2.0);
}

}  // namespace
}  // namespace pmsim::ui
