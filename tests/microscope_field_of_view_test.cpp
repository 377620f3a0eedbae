// Thin sections at physical scale: the field of view is field_number / magnification, grain sizes
// in pixels scale with the magnification, the stage translates the section under the crosshair and
// turns it about that point, and the conoscopic figure is that of the grain under the crosshair.
// Label images (core/microscope/grain_labels.h) are the ground truth compared: they map pixels to
// grains with the same section_point_from_pixel the renderer samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/microscope/grain_labels.h"
#include "core/microscope/optical_domains.h"
#include "core/microscope/pixel_view.h"
#include "core/microscope/section_map.h"
#include "core/microscope/view_geometry.h"

using namespace pmsim;

namespace {

Scene section_scene(int width, int height, double magnification) {
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = "granite_hand_placed";
  s.render.width = width;
  s.render.height = height;
  s.objective.magnification = magnification;
  return s;
}

using Labels = std::vector<std::uint16_t>;

std::uint16_t at(const Labels& l, int w, int x, int y) { return l[static_cast<std::size_t>(y) * w + x]; }

// Pixels of grain k with a 4-neighbour of another label (or on the image edge): where a
// sub-pixel shift of the grid can change the label.
long long boundary_pixels(const Labels& l, int w, int h, std::uint16_t k) {
  long long n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (at(l, w, x, y) != k) continue;
      const bool edge = x == 0 || y == 0 || x == w - 1 || y == h - 1;
      if (edge || at(l, w, x - 1, y) != k || at(l, w, x + 1, y) != k || at(l, w, x, y - 1) != k ||
          at(l, w, x, y + 1) != k)
        ++n;
    }
  return n;
}

bool touches_edge(const Labels& l, int w, int h, std::uint16_t k) {
  for (int x = 0; x < w; ++x)
    if (at(l, w, x, 0) == k || at(l, w, x, h - 1) == k) return true;
  for (int y = 0; y < h; ++y)
    if (at(l, w, 0, y) == k || at(l, w, w - 1, y) == k) return true;
  return false;
}

}  // namespace

TEST(FieldOfView, FieldNumberOverMagnificationSpansTheShorterSide) {
  Scene s = section_scene(640, 480, 10.0);
  s.eyepiece.field_number_mm = 22.0;
  EXPECT_DOUBLE_EQ(field_of_view_mm(s), 2.2);
  EXPECT_DOUBLE_EQ(mm_per_pixel(s, 640, 480), 2.2 / 480);
  // The two ends of the shorter (vertical) side are FOV/2 north and south of the crosshair point.
  s.stage.x_mm = 1.5;
  s.stage.y_mm = -0.75;
  const glm::dvec2 top = section_point_from_pixel(s, 640, 480, 320.0, 0.0);
  const glm::dvec2 bottom = section_point_from_pixel(s, 640, 480, 320.0, 480.0);
  const glm::dvec2 centre = section_point_from_pixel(s, 640, 480, 320.0, 240.0);
  // 1e-12 mm: a few ulps of millimetre-sized sums.
  EXPECT_NEAR(top.y - bottom.y, 2.2, 1e-12);
  EXPECT_NEAR(centre.x, 1.5, 1e-12);
  EXPECT_NEAR(centre.y, -0.75, 1e-12);
  s.objective.magnification = 40.0;
  EXPECT_DOUBLE_EQ(field_of_view_mm(s), 0.55);
}

// Doubling the magnification halves the field: the central half of an M× image of 2W × 2H pixels
// is, pixel for pixel, the 2M× image of W × H (same mm per pixel, same pixel centres), and a grain's
// area in pixels at 2M× is four times that at M× on the same pixel grid.
TEST(FieldOfView, GrainSizesInPixelsScaleWithMagnification) {
  const auto section = load_section("granite_hand_placed");
  bool compared_area = false;
  for (const double m : {2.5, 4.0, 10.0, 20.0}) {
    const int w = 96, h = 80;
    const Labels big = grain_label_image(section_scene(2 * w, 2 * h, m), *section);
    const Labels zoom = grain_label_image(section_scene(w, h, 2 * m), *section);
    long long differ = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) differ += at(big, 2 * w, x + w / 2, y + h / 2) != at(zoom, w, x, y);
    // The two maps compute each pixel centre by different roundings (FOV/2 scaled differently):
    // only a centre within ~1e-15 mm of a grain boundary can flip, so at most a handful of the
    // 7680 pixels (0.1 %).
    EXPECT_LE(differ, w * h / 1000) << "at " << m << "x";
    // Area ratio: the grain with the most pixels that lies wholly inside the 2M× field.
    const Labels base = grain_label_image(section_scene(w, h, m), *section);
    std::map<std::uint16_t, long long> area_m, area_2m;
    for (auto k : base) ++area_m[k];
    for (auto k : zoom) ++area_2m[k];
    std::uint16_t best = 0;
    for (const auto& [k, n] : area_2m)
      if (k != 0 && !touches_edge(zoom, w, h, k) && !touches_edge(base, w, h, k) && area_m[k] >= 100 &&
          (best == 0 || n > area_2m[best]))
        best = k;
    if (best == 0) continue;  // no grain small enough at this magnification: try the next
    compared_area = true;
    // Each boundary pixel of the M× image may or may not hold the grain (its centre samples a
    // boundary anywhere across the pixel): an error of up to one pixel there, four at 2M×, plus
    // one per boundary pixel of the 2M× image. Were the field not to shrink (the old behaviour),
    // the two areas would be equal: a 3× error, far beyond this bound.
    const double tol = 4.0 * boundary_pixels(base, w, h, best) + boundary_pixels(zoom, w, h, best);
    EXPECT_NEAR(static_cast<double>(area_2m[best]), 4.0 * area_m[best], tol)
        << "grain " << best << " at " << m << "x and " << 2 * m << "x";
    EXPECT_LT(tol, 3.0 * area_m[best]) << "the bound must not admit an unscaled field";
  }
  EXPECT_TRUE(compared_area) << "no grain fits wholly in any field tried";
}

// stage.x_mm = dx moves the section point under every pixel by dx: the image shifts by
// dx / mm_per_pixel pixels to the left (the crosshair now sees what was dx east of it); stage.y_mm
// = dy shifts it down by dy / mm_per_pixel.
TEST(FieldOfView, StageTranslationShiftsTheImageByWholePixels) {
  const auto section = load_section("granite_hand_placed");
  const int w = 120, h = 100, sx = 13, sy = 7;
  Scene s = section_scene(w, h, 10.0);
  const Labels base = grain_label_image(s, *section);
  s.stage.x_mm = sx * mm_per_pixel(s, w, h);
  s.stage.y_mm = -sy * mm_per_pixel(s, w, h);
  const Labels moved = grain_label_image(s, *section);
  long long differ = 0, compared = 0;
  for (int y = 0; y + sy < h; ++y)
    for (int x = 0; x + sx < w; ++x) {
      differ += at(moved, w, x, y) != at(base, w, x + sx, y + sy);
      ++compared;
    }
  // Same section points up to the rounding of x·mm_per_pixel + dx: only centres within ~1e-15
  // mm of a boundary can flip (0.1 % bound, as above).
  EXPECT_LE(differ, compared / 1000);
  // And the shift is real: the image did change (a section of one grain would make this vacuous).
  long long changed = 0;
  for (std::size_t i = 0; i < base.size(); ++i) changed += base[i] != moved[i];
  EXPECT_GT(changed, static_cast<long long>(base.size()) / 20);
}

// A turn of the stage by 90° turns the image by 90° counter-clockwise about the crosshair pixel,
// wherever the crosshair is on the section: pixel (x, y) of the turned image shows what pixel
// (W − 1 − y, x) showed (square image, even size: pixel centres map onto pixel centres).
TEST(FieldOfView, StageRotationTurnsAboutTheCrosshairPoint) {
  const auto section = load_section("granite_hand_placed");
  const int n = 100;
  Scene s = section_scene(n, n, 10.0);
  s.stage.x_mm = 0.3;
  s.stage.y_mm = -0.2;
  const Labels base = grain_label_image(s, *section);
  s.stage_deg = 90.0;
  const Labels turned = grain_label_image(s, *section);
  long long differ = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) differ += at(turned, n, x, y) != at(base, n, n - 1 - y, x);
  // cos 90° is 6e-17 in floating point, not 0: only boundary-grazing centres may flip (0.1 %).
  EXPECT_LE(differ, n * n / 1000);
  // Turned about the section's origin instead (the stage before stage.x_mm/y_mm), the pixel
  // (W − 1 − y, x) would show R(−90°)·c + … instead of c + …: a shift by |c − R(−90°)c| = 0.51 mm,
  // ~26 pixels here, which this comparison would see on most pixels. It must also see a change.
  long long changed = 0;
  for (std::size_t i = 0; i < base.size(); ++i) changed += base[i] != turned[i];
  EXPECT_GT(changed, static_cast<long long>(base.size()) / 20);
}

// Conoscopic view of a section: the figure is that of the grain under the crosshair, at any stage
// position.
TEST(FieldOfView, ConoscopicFigureShowsTheGrainUnderTheCrosshair) {
  const auto section = load_section("granite_hand_placed");
  Scene s = section_scene(32, 32, 10.0);
  s.mode = ViewMode::Cono;
  s.bertrand_in = true;
  int distinct = 0, last = -1;
  for (const double x : {-0.8, -0.3, 0.2, 0.7}) {
    s.stage.x_mm = x;
    s.stage.y_mm = 0.5 * x;
    const OpticalDomains domains = optical_domains(s);
    const auto view = pixel_view(s, domains);
    ASSERT_TRUE(view && !view->units.empty());
    const int expected = section->domain_at({x, 0.5 * x});
    for (const EvalUnit& u : view->units) EXPECT_EQ(u.domain, expected) << "stage at " << x << " mm";
    distinct += expected != last;
    last = expected;
  }
  EXPECT_GE(distinct, 2) << "the stage positions tried all lie in one grain: the test shows nothing";
}
