// The progressive renderer's contract with the UI: restart never blocks for a pass, snapshot only
// reports new images, invalid scenes keep the previous one, converged images carry their stats.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "core/io/input_error.h"
#include "core/render/progressive_renderer.h"

using namespace pmsim;

namespace {
Scene figure(int size) {
  Scene s;
  s.mode = ViewMode::Cono;
  s.bertrand_in = true;
  s.sample.mineral = "calcite";
  s.sample.optic_axis = {0, 0, 1};
  s.sample.thickness_um = 1000;
  s.objective.na = 0.85;
  s.render.width = s.render.height = size;
  return s;
}
}  // namespace

TEST(ProgressiveRenderer, ConvergesAndReportsItsStatistics) {
  ProgressiveRenderer r(2);
  r.restart(figure(64));
  ASSERT_TRUE(r.wait(60.0));
  RenderImage img;
  ASSERT_TRUE(r.snapshot(img));
  EXPECT_TRUE(img.converged);
  EXPECT_LT(img.error_estimate, 0.5);  // render.tolerance default
  EXPECT_GE(img.passes, 2);
  EXPECT_EQ(img.width, 64);
  EXPECT_EQ(img.rgb.size(), 64u * 64u * 3u);
  EXPECT_FALSE(img.model_report.empty());
  for (float v : img.rgb) ASSERT_TRUE(std::isfinite(v));
  // Nothing new since: snapshot says so.
  EXPECT_FALSE(r.snapshot(img));
}

TEST(ProgressiveRenderer, RestartCancelsImmediatelyAndBumpsTheGeneration) {
  ProgressiveRenderer r(2);
  Scene big = figure(512);
  big.render.wavelengths = 4000;  // long enough to still be running when restarted
  r.restart(big);
  const auto t0 = std::chrono::steady_clock::now();
  r.restart(figure(32));
  const double restart_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  // Cancellation is checked per block of units; set-up of the big scene is cancellable too.
  EXPECT_LT(restart_ms, 2000.0);
  ASSERT_TRUE(r.wait(60.0));
  RenderImage img;
  ASSERT_TRUE(r.snapshot(img));
  EXPECT_EQ(img.width, 32);
  EXPECT_EQ(img.generation, 2u);
}

TEST(ProgressiveRenderer, InvalidSceneThrowsAndKeepsThePreviousImage) {
  ProgressiveRenderer r(1);
  r.restart(figure(16));
  ASSERT_TRUE(r.wait(60.0));
  Scene bad = figure(16);
  bad.objective.na = 1.5;
  EXPECT_THROW(r.restart(bad), InputError);
  RenderImage img;
  ASSERT_TRUE(r.snapshot(img));
  EXPECT_EQ(img.generation, 1u);
}

TEST(ProgressiveRenderer, FixedSampleCountsAreExact) {
  Scene s = figure(16);
  s.render.wavelengths = 24;
  const RenderImage img = ProgressiveRenderer::render(s, 1);
  EXPECT_EQ(img.wavelengths, 24);
  EXPECT_EQ(img.passes, 1);
  EXPECT_TRUE(img.converged);
}
