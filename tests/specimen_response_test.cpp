// The specimen response and the instrument applied to it (issue 21, core/specimen/
// specimen_response.h): images composed from one traced response against fresh renders at the
// same settings, on a one-grain quartz section with relief (a 120 µm square, optic axis in the
// section plane at 20°, 30 µm; a 200 µm field of 4 µm pixels).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "core/base/units.h"
#include "core/render/progressive_renderer.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "core/specimen/forward_plane_light.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/section_slab.h"
#include "core/specimen/traced_specimen.h"
#include "tests/section_file_fixture.h"

namespace {

namespace fs = std::filesystem;
constexpr int kPixels = 50;

// One quartz grain filling the field, its optic axis in the section at 20°.
std::string one_grain_file() {
  return section_test::write_section(
      "quartz.json", {section_test::grain_with_axis_in_plane("quartz", 0.0, 0.0, 0.5, 20.0)}, 0.12);
}

pmsim::Scene scene() {
  static const std::string file = one_grain_file();
  pmsim::Scene s;
  s.sample.type = pmsim::SampleType::Section;
  s.sample.section = file;
  s.analyzer_in = true;
  s.objective.magnification = 100.0;
  s.render.width = s.render.height = kPixels;
  s.render.spp = 24;  // 8 passes of 3 traces a pixel: each half has traced every band's 4 λ
  s.render.tolerance_de2000 = 0.0;
  return s;
}

// Mean CIEDE2000 over the pixels inside a centred square of half-size `half_px` (the grain's
// interior and its outline band: where refraction moves light, noise is largest).
double mean_de(const pmsim::RenderImage& a, const pmsim::RenderImage& b, int half_px) {
  const glm::dvec3 white = pmsim::illuminant_white_xyz(pmsim::Illuminant::D65);
  double sum = 0.0;
  int n = 0;
  for (int y = kPixels / 2 - half_px; y < kPixels / 2 + half_px; ++y)
    for (int x = kPixels / 2 - half_px; x < kPixels / 2 + half_px; ++x) {
      const std::size_t i = 3 * (std::size_t(y) * kPixels + std::size_t(x));
      sum += pmsim::ciede2000(pmsim::xyz_to_lab(glm::dvec3(a.xyz[i], a.xyz[i + 1], a.xyz[i + 2]), white),
                              pmsim::xyz_to_lab(glm::dvec3(b.xyz[i], b.xyz[i + 1], b.xyz[i + 2]), white));
      ++n;
    }
  return sum / n;
}

// The response composed at the scene's own settings against the forward image renderer, which
// traces the analyzer's projection directly (forward_plane_light.h): the same physics by another
// path. Tolerance: the two differ by their sampling noise (the same seeds, but other per-ray
// work) and by the aplanatic map against the older projection of the vibrations (O(sin²θ) with
// θ ≤ 0.03 rad under the stopped-down condenser: < 1e-3); 2 ΔE00 is 2× the split-half estimate
// these 8-pass renders report in the grain's interior.
TEST(SpecimenResponse, ComposedMatchesTheForwardImageRenderer) {
  for (double stage : {0.0, 30.0}) {
    pmsim::Scene s = scene();
    s.stage_deg = stage;
    const pmsim::RenderImage composed = pmsim::render_traced_specimen(s);
    const auto slab = pmsim::section_slab(s);
    const pmsim::RenderImage direct = pmsim::render_plane_light_forward(*slab, pmsim::plane_light_options(s));
    const double de = mean_de(composed, direct, 12);
    std::printf("  stage %.0f°: composed vs forward image, grain interior mean ΔE00 %.3f\n", stage, de);
    EXPECT_LT(de, 2.0);
  }
}

// One Disc response at stage 0°, composed at 35° with the polarizer and analyzer turned, against a
// fresh render at those settings. Tolerance: the bilinear resampling of a grid turned by 35°
// (a ≤ ½-pixel blur, in the interior of a uniform grain invisible) plus the two renders' noise: 2.
TEST(SpecimenResponse, OneDiscResponseServesAnyStageAndPolars) {
  pmsim::Scene s = scene();
  const pmsim::ResponseProgress disc = pmsim::render_traced_response(s, pmsim::ResponseCoverage::Disc);
  ASSERT_TRUE(disc.response);
  pmsim::Scene t = s;
  t.stage_deg = 35.0;
  t.polarizer_deg = 10.0;
  t.analyzer_deg = 100.0;
  EXPECT_TRUE(pmsim::same_specimen_response(s, t));
  const pmsim::RenderImage composed = pmsim::compose_progress(disc, pmsim::instrument_settings(t));
  const pmsim::RenderImage fresh = pmsim::render_traced_specimen(t);
  const double de = mean_de(composed, fresh, 10);
  std::printf("  disc response at 35°, polars 10°/100°: mean ΔE00 %.3f against a fresh render\n", de);
  EXPECT_LT(de, 2.0);
  t.focus_um = 5.0;
  EXPECT_FALSE(pmsim::same_specimen_response(s, t));
}

// The gypsum plate applied to the traced response against the flat image with the plate (the
// progressive renderer's analytic plate): the grain interior, where nothing refracts, has the
// same colour. Tolerance 3: the traced image's noise, the slab's polishing roughness (0.15 µm of
// thickness) and the condenser cone's spread of retardation against the flat image's normal ray.
TEST(SpecimenResponse, GypsumPlateOnTheTracedResponseMatchesTheFlatImage) {
  pmsim::Scene s = scene();
  s.compensator = pmsim::Compensator::Gypsum;
  s.stage_deg = 25.0;
  ASSERT_TRUE(pmsim::is_traced_specimen(s));
  const pmsim::RenderImage traced = pmsim::render_traced_specimen(s);
  pmsim::Scene f = s;
  f.optics.relief = false;
  f.render.tolerance_de2000 = 0.5;
  f.render.spp = 0;
  const pmsim::RenderImage flat = pmsim::ProgressiveRenderer::render(f, 0);
  const double de = mean_de(traced, flat, 8);
  std::printf("  gypsum plate: traced response vs flat image, interior mean ΔE00 %.3f\n", de);
  EXPECT_LT(de, 3.0);
}

// A cap stop is not convergence: tolerance far below what 2 passes reach.
TEST(SpecimenResponse, CapStopIsNotConverged) {
  pmsim::Scene s = scene();
  s.render.spp = 6;
  s.render.tolerance_de2000 = 1e-6;
  const pmsim::RenderImage img = pmsim::render_traced_specimen(s);
  EXPECT_FALSE(img.converged);
  EXPECT_EQ(img.stopped, "cap");
  ASSERT_TRUE(img.error_estimate.has_value());
  for (float v : img.rgb) ASSERT_TRUE(std::isfinite(v));
}

}  // namespace
