// One pipeline, chosen in core (issue 21, core/specimen/instrument_response.h): which source serves
// a scene while only the instrument changes, and the one response type pmsim-render's --sweep,
// the app's render feed and the bench compose from. Small images (16–24²), few traces: the
// physics of each response is tested in specimen_response_test and figure_response_test; here,
// that the dispatch picks the right one and composes exactly what that response composes.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "core/io/scene_file.h"
#include "core/render/progressive_renderer.h"
#include "core/specimen/instrument_response.h"
#include "core/specimen/traced_specimen.h"
#include "tests/section_file_fixture.h"

namespace {

using namespace pmsim;

// One quartz grain with its optic axis in the section at 30°, 30 µm: a traced specimen.
Scene traced_scene() {
  const std::string p = section_test::write_section(
      "quartz.json", {section_test::grain_with_axis_in_plane("quartz", 0.0, 0.0, 0.5, 30.0)}, 0.12);
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = p;
  s.analyzer_in = true;
  s.objective.magnification = 100.0;
  s.render.width = s.render.height = 16;
  s.render.spp = 6;
  s.render.tolerance_de2000 = 0.0;
  return s;
}

// A biaxial acute-bisectrix figure.
Scene figure_scene() {
  const nlohmann::json j = {
      {"type", "microscope"},
      {"mode", "cono"},
      {"objective", {{"magnification", 50}, {"na", 0.85}}},
      {"condenser", {{"na", 0.9}}},
      {"sample", nlohmann::json::parse(R"({"type": "plate", "crystal": {"nalpha": 1.60, "nbeta": 1.61,
        "ngamma": 1.64}, "thickness_um": 60, "x_axis": [1, 0, 0], "z_axis": [0, 0, 1]})")},
      {"render", {{"width", 24}, {"height", 24}}}};
  return scene_from_json(j, "instrument_response_test");
}

double max_abs_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double m = a.size() == b.size() ? 0.0 : INFINITY;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) m = std::max(m, std::abs(double(a[i]) - b[i]));
  return m;
}

TEST(InstrumentResponse, KindFollowsTheViewAndTheSlot) {
  Scene traced = traced_scene();
  EXPECT_EQ(response_kind(traced), ResponseKind::Traced);
  traced.compensator = Compensator::Gypsum;  // applied to the traced response
  EXPECT_EQ(response_kind(traced), ResponseKind::Traced);
  traced.optics.relief = false;  // the flat section image: its probes, and its plan for the accessory
  EXPECT_EQ(response_kind(traced), ResponseKind::Flat);
  traced.compensator = Compensator::None;
  EXPECT_EQ(response_kind(traced), ResponseKind::Flat);
  Scene plate = traced;  // one evaluation for the whole field: rendered per setting
  plate.sample.type = SampleType::Plate;
  plate.sample.mineral = "quartz";
  plate.sample.thickness_um = 30.0;
  EXPECT_EQ(response_kind(plate), ResponseKind::None);

  Scene figure = figure_scene();
  EXPECT_EQ(response_kind(figure), ResponseKind::Figure);
  figure.compensator = Compensator::Gypsum;  // the figure's plan evaluated in the frame's train
  EXPECT_EQ(response_kind(figure), ResponseKind::Figure);
  figure.optics.lens_depth = 2;  // ghost light, reckoned per train in the plan: rendered per setting
  EXPECT_EQ(response_kind(figure), ResponseKind::None);
  figure.optics.lens_depth = 1;
  figure.compensator = Compensator::None;
  figure.bertrand_in = false;
  EXPECT_EQ(response_kind(figure), ResponseKind::None);
}

TEST(InstrumentResponse, ServesOnlyInstrumentChangesOnAViewThatHasOne) {
  const Scene traced = traced_scene();
  Scene next = traced;
  next.stage_deg = 37.0;
  next.polarizer_deg = 10.0;
  next.compensator = Compensator::QuartzWedge;
  next.compensator_position = 0.4;
  next.render.exposure_ev = 1.0;
  EXPECT_TRUE(response_serves(traced, next));
  next.focus_um = traced.focus_um + 2.0;  // the specimen's response itself changes
  EXPECT_FALSE(response_serves(traced, next));
  // Another section is not loaded to be compared (the app asks on its UI thread, and loading a
  // rock grows it): a path that does not exist would throw if it were.
  next = traced;
  next.sample.section = (section_test::scratch_dir() / "no_such_section.json").string();
  EXPECT_FALSE(response_serves(traced, next));

  const Scene figure = figure_scene();
  next = figure;
  next.stage_deg = 20.0;
  next.analyzer_in = false;
  EXPECT_TRUE(response_serves(figure, next));
  next.compensator = Compensator::Gypsum;  // the figure's plan evaluated in the frame's train
  EXPECT_TRUE(response_serves(figure, next));
  Scene ghosts = figure;
  ghosts.optics.lens_depth = 2;
  next = ghosts;
  next.compensator = Compensator::Gypsum;  // out of the reach of a figure with ghost light
  EXPECT_FALSE(response_serves(ghosts, next));

  Scene flat = traced;
  flat.optics.relief = false;
  next = flat;
  next.stage_deg = 50.0;
  EXPECT_TRUE(response_serves(flat, next));
  next.compensator = Compensator::Gypsum;  // the canvas's plan evaluated in the frame's train
  EXPECT_TRUE(response_serves(flat, next));
  next = ghosts;
  next.compensator = Compensator::Gypsum;
  EXPECT_FALSE(response_serves(next, next));  // no response: every setting is rendered
  EXPECT_FALSE(response_serves(traced, flat));
  EXPECT_FALSE(response_serves(traced, figure));
  EXPECT_THROW(render_instrument_response(next, ResponseCoverage::Field), std::invalid_argument);
}

TEST(InstrumentResponse, TracedComposesAsTheSingleRender) {
  const Scene s = traced_scene();
  const std::optional<InstrumentResponse> r = render_instrument_response(s, ResponseCoverage::Field);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->kind(), ResponseKind::Traced);
  EXPECT_STREQ(r->coverage_name(), "field");
  EXPECT_FALSE(r->empty());
  const RenderImage composed = r->compose(instrument_settings(s));
  const RenderImage single = render_microscope_scene(s);
  // The same traced response (its samples are seeded by pixel and pass, not by thread) composed at
  // the same settings: bit for bit, and the status is the single render's.
  EXPECT_EQ(max_abs_difference(composed.xyz, single.xyz), 0.0);
  EXPECT_EQ(r->status().passes, single.passes);
  EXPECT_EQ(r->status().samples_per_pixel, single.samples_per_pixel);
  EXPECT_EQ(r->status().stopped, "cap");  // tolerance 0: only the cap stops it
  EXPECT_FALSE(r->status().converged);

  std::atomic<bool> cancel{true};
  EXPECT_FALSE(render_instrument_response(s, ResponseCoverage::Field, nullptr, &cancel).has_value());
}

TEST(InstrumentResponse, FigureReportsItsOwnRenderThenComposesFromItsProbes) {
  const Scene s = figure_scene();
  int rendering = 0, complete = 0;
  const std::optional<InstrumentResponse> r = render_instrument_response(
      s, ResponseCoverage::Field, [&](const InstrumentResponse& state) {
        if (state.empty()) {
          ++rendering;
          EXPECT_THROW(state.compose(instrument_settings(s)), std::logic_error);
        } else {
          ++complete;
        }
      });
  ASSERT_TRUE(r.has_value());
  EXPECT_GE(rendering, 1);  // the figure's own passes, before its probes
  EXPECT_EQ(complete, 1);
  EXPECT_EQ(r->kind(), ResponseKind::Figure);
  EXPECT_STREQ(r->coverage_name(), "figure");
  EXPECT_EQ(r->status().stopped, "tolerance");
  Scene at = s;
  at.polarizer_deg = 25.0;
  at.analyzer_deg = 70.0;
  at.render.wavelengths = r->status().wavelengths;  // the probes' spectral level
  // Nine probes combined in float with weights ≤ 1.5 from values ≤ 1: a few ulps of XYZ ≈ 1
  // (figure_response_test's bound, 1e-5, ~10² above the rounding).
  EXPECT_LT(max_abs_difference(r->compose(instrument_settings(at)).xyz, ProgressiveRenderer::render(at).xyz), 1e-5);
}

}  // namespace
