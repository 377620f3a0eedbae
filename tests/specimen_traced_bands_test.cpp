// render.wavelengths reaches the traced specimens (issue 21: "traced renders honour ...
// render.wavelengths like every other"): the bands of a traced response are the scene's count,
// within the traced renderers' floor between crossed polars and their memory cap.
#include <gtest/gtest.h>

#include "core/microscope/scene.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/plane_light_image.h"
#include "core/specimen/traced_specimen.h"

namespace {

// A 16² garnet grain mount, one pass: the response's bands are fixed before any tracing.
pmsim::Scene small_mount(int wavelengths, bool analyzer_in) {
  pmsim::Scene s;
  s.sample.type = pmsim::SampleType::Grains;
  s.sample.mineral = "almandine";
  s.analyzer_in = analyzer_in;
  s.render.width = s.render.height = 16;
  s.render.spp = 1;
  s.render.wavelengths = wavelengths;
  return s;
}

int response_bands(const pmsim::Scene& s) {
  const pmsim::ResponseProgress p = pmsim::render_traced_response(s, pmsim::ResponseCoverage::Field);
  return p.response ? p.response->bands.count() : -1;
}

}  // namespace

TEST(SpecimenTracedBands, RenderWavelengthsSetsTheTracedBands) {
  // Unset (0): the renderer's own choice, unchanged.
  EXPECT_EQ(pmsim::plane_light_options(small_mount(0, false)).bands, pmsim::PlaneLightOptions{}.bands);
  EXPECT_EQ(pmsim::plane_light_options(small_mount(20, false)).bands, 20);
  // Above the cap: the cap (render.wavelengths may be up to 4001; the response's colour store
  // grows with the bands).
  EXPECT_EQ(pmsim::plane_light_options(small_mount(4001, false)).bands, pmsim::kMaxTracedBands);
  // The response traced between crossed polars: 48 bands asked, 48 traced; 8 asked, the floor
  // of 32 (12.5 nm bands, a tenth of the period of sin²(πΓ/λ) at the top of the second order).
  EXPECT_EQ(response_bands(small_mount(48, true)), 48);
  EXPECT_EQ(response_bands(small_mount(8, true)), pmsim::kCrossedPolarBands);
}
