// pmsim-render --sweep, --progress and the stats' "stopped" through the built binary (issue 21):
// a sweep's frames are the images of separate renders with --set KEY=value; bad sweep input exits 2
// and writes nothing; the stats say why a render stopped, and converged only at the tolerance; the
// progress line goes to stderr only when asked for (or to a terminal). Every render is 32² or less.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/io/image_file.h"
#include "tests/render_cli_run.h"

namespace fs = std::filesystem;
using pmsim::test::cli_temp_dir;
using pmsim::test::kRenderBinary;
using pmsim::test::run_render_cli;

namespace {

const std::string kPlate = std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/quartz_plate_45.json";
const std::string kSection = std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/quartz_section_ortho.json";
const std::string kSmall = " --set render.width=32 --set render.height=32";

// A fresh, empty scratch folder for one test.
std::string fresh_dir(const std::string& tag) {
  const std::string d = cli_temp_dir("sweep_" + tag);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::size_t files_in(const std::string& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir))
    if (e.path().filename() != "stderr.txt") ++n;
  return n;
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream f(path);
  return nlohmann::json::parse(f);
}

}  // namespace

// The flat renderer is deterministic (every unit's spectral sum in a fixed order, the same levels
// for the same scene), and each frame's scene is made by the same setting function --set uses: so
// a frame is not merely close to the separate render, it is the same image, 8-bit value for value.
TEST(RenderSweepCli, FlatFramesAreTheSeparateRendersExactly) {
  ASSERT_TRUE(fs::exists(kRenderBinary)) << kRenderBinary << " not built";
  const std::string d = fresh_dir("flat");
  const pmsim::test::CliRun r = run_render_cli(
      kPlate + kSmall + " --sweep polarizer_deg=0:90:45 --out " + d + "/pol_%02d.png --stats " + d + "/s.json", d);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(d + "/pol_03.png"));  // 0, 45, 90: three frames, numbered from 0
  const char* values[] = {"0", "45", "90"};
  for (int i = 0; i < 3; ++i) {
    char frame[64];
    std::snprintf(frame, sizeof frame, "/pol_%02d.png", i);
    const std::string single = d + "/single_" + values[i] + ".png";
    ASSERT_EQ(run_render_cli(kPlate + kSmall + " --set polarizer_deg=" + values[i] + " --out " + single, d).code, 0);
    const pmsim::LoadedImage a = pmsim::read_image(d + frame), b = pmsim::read_image(single);
    ASSERT_EQ(a.width, 32);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_TRUE(a.pixels == b.pixels) << "frame " << i << " differs from --set polarizer_deg=" << values[i];
    EXPECT_EQ(a.metadata["pmsim:scene"], b.metadata["pmsim:scene"]) << i;
  }
  // Polarizer at 0° and 90° against the analyzer at 90°: crossed and parallel polars differ.
  EXPECT_FALSE(pmsim::read_image(d + "/pol_00.png").pixels == pmsim::read_image(d + "/pol_02.png").pixels);
  const nlohmann::json s = read_json(d + "/s.json");
  ASSERT_EQ(s["frames"].size(), 3u);
  EXPECT_EQ(s["sweep"]["key"], "polarizer_deg");
  EXPECT_EQ(s["frames"][1]["value"], 45.0);
  EXPECT_EQ(s["frames"][2]["file"], d + "/pol_02.png");
  EXPECT_TRUE(s["response"].is_null());  // a flat scene: every frame rendered on its own
  for (const auto& f : s["frames"]) EXPECT_EQ(f["stopped"], "tolerance");
  EXPECT_EQ(s["stopped"], "tolerance");
  EXPECT_TRUE(s["converged"].get<bool>());
}

TEST(RenderSweepCli, BadSweepInputExitsTwoNamingTheFlagAndWritesNothing) {
  ASSERT_TRUE(fs::exists(kRenderBinary)) << kRenderBinary << " not built";
  const std::string d = fresh_dir("bad");
  const std::string out = " --out " + d + "/f_%03d.png --stats " + d + "/s.json";
  struct Case {
    std::string args, named;
  };
  const Case cases[] = {
      {"--sweep sample.thickness_um=10:30:10" + out, "sample.thickness_um"},  // not an instrument key
      {"--sweep polarizer_deg=0:90:0" + out, "STEP 0"},
      {"--sweep polarizer_deg=0:90:-15" + out, "STEP -15"},
      {"--sweep polarizer_deg=90:0:15" + out, "START 90"},
      {"--sweep stage_deg=0:360:0.05" + out, "more than 3600 frames"},
      {"--sweep polarizer_deg=0:ninety:15" + out, "'ninety'"},
      {"--sweep polarizer_deg=0:90" + out, "0:90"},
      {"--sweep polarizer_deg=0:90:15:5" + out, "0:90:15:5"},
      {"--sweep polarizer_deg" + out, "KEY=START:STOP:STEP"},
      {"--sweep polarizer_deg=0:90:inf" + out, "'inf'"},
      // The value each frame sets is checked as --set checks it, before anything is rendered.
      {"--sweep compensator_position=0:1.5:0.5 --set compensator=gypsum" + out, "compensator_position"},
      {"--sweep polarizer_deg=0:90:45 --out " + d + "/f.png", "--out"},           // no field
      {"--sweep polarizer_deg=0:90:45 --out " + d + "/f_%d_%d.png", "more than one field"},
      {"--sweep polarizer_deg=0:90:45 --out " + d + "/f_%s.png", "'%s'"},
      {"--sweep polarizer_deg=0:90:45 --out " + d + "/f_%-3d.png", "'%-'"},
      {"--sweep polarizer_deg=0:90:45 --out " + d + "/f_%x.png", "'%x'"},
      {"--sweep polarizer_deg=0:90:45 --labels " + d + "/l.png" + out, "--labels"},
  };
  for (const Case& c : cases) {
    const pmsim::test::CliRun r = run_render_cli(kPlate + kSmall + " " + c.args, d);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.named), std::string::npos) << c.args << "\n" << r.err;
    if (c.args.find("thickness") == std::string::npos && c.args.find("compensator") == std::string::npos &&
        c.args.find("--labels") == std::string::npos) {
      EXPECT_TRUE(r.err.find("--sweep") != std::string::npos || r.err.find("--out") != std::string::npos) << r.err;
    }
    EXPECT_EQ(files_in(d), 0u) << c.args;
  }
}

// "stopped" says why a render ended; converged means "estimate below render.tolerance" and nothing
// else, so a render a cap ended with a tiny tolerance unmet is not converged.
TEST(RenderSweepCli, StatsSayWhyTheRenderStopped) {
  ASSERT_TRUE(fs::exists(kRenderBinary)) << kRenderBinary << " not built";
  const std::string d = fresh_dir("stopped");
  // Flat, to its tolerance.
  ASSERT_EQ(run_render_cli(kPlate + kSmall + " --out " + d + "/a.png --stats " + d + "/a.json", d).code, 0);
  nlohmann::json s = read_json(d + "/a.json");
  EXPECT_EQ(s["stopped"], "tolerance");
  EXPECT_TRUE(s["converged"].get<bool>());
  EXPECT_LT(s["error_estimate"].get<double>(), 0.5);
  // Flat, capped by render.wavelengths before a tolerance of 0.001: the estimate at the stop is kept.
  ASSERT_EQ(run_render_cli(kPlate + kSmall + " --set render.wavelengths=16 --set render.tolerance=0.001 --out " + d +
                               "/b.png --stats " + d + "/b.json",
                           d)
                .code,
            0);
  s = read_json(d + "/b.json");
  EXPECT_EQ(s["stopped"], "cap");
  EXPECT_FALSE(s["converged"].get<bool>());
  ASSERT_TRUE(s["error_estimate"].is_number());
  EXPECT_GE(s["error_estimate"].get<double>(), 0.001);
  // Traced (a section slab with relief), capped by render.spp = 2 traces a pixel.
  ASSERT_EQ(run_render_cli(kSection + kSmall + " --set render.spp=2 --set render.tolerance=0.001 --out " + d +
                               "/c.png --stats " + d + "/c.json",
                           d)
                .code,
            0);
  s = read_json(d + "/c.json");
  EXPECT_EQ(s["stopped"], "cap");
  EXPECT_FALSE(s["converged"].get<bool>());
  EXPECT_TRUE(s.contains("error_estimate"));
}

TEST(RenderSweepCli, ProgressLineOnlyWhenAskedFor) {
  ASSERT_TRUE(fs::exists(kRenderBinary)) << kRenderBinary << " not built";
  const std::string d = fresh_dir("progress");
  // stderr is a file here, not a terminal: nothing extra without --progress.
  pmsim::test::CliRun r = run_render_cli(kPlate + kSmall + " --out " + d + "/a.png", d);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  r = run_render_cli(kPlate + kSmall + " --progress --out " + d + "/b.png", d);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("pass 1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ΔE"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("stopped: tolerance"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.back(), '\n');
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << "carriage returns are for terminals only";
}

// A traced section swept over the stage: its response is traced once over the disc the field
// sweeps (frame angle 0°) and the 30° frame composed from it by bilinear resampling of that grid,
// against a separate render with --set stage_deg=30. Granite at 10× on 32² (62 µm a
// pixel), 16 traces a pixel (4 would not see a one-pixel misregistration: see below).
//
// The tolerance, in mean |Δ| of linear RGB over the image (mean level ~0.05–0.07), from what the
// two images are — measured on this scene and size (2 idle cores, issue 21):
//   - noise: each 16-trace image lies 0.010–0.011 from its own 256-trace render; the 30° frame and
//     the 30° render trace different points, so their noise is independent: ≤ 0.011 + 0.011.
//     (The 0° frame and the 0° render share their sample points, so less there.)
//   - resampling: the 30° frame reads the 0°-frame grid bilinearly between its points (a blur of
//     up to a pixel on a field whose grain boundaries and cracks are a pixel wide), and its colour
//     from a chroma subgrid of another origin: the 256-trace frame and render, nearly noise-free
//     (0.003 each), differ by 0.017 at 30° (0.007 at 0°, the chroma subgrid and noise only).
//   Sum (an upper bound: the parts partly cancel): 0.022 + 0.017 ≈ 0.039. Measured: 0.024 (and
//   0.009 for the 0° frame against a 0° render). What the bound rejects: the frame against the
//   30° render shifted by one pixel, 0.039 (just at it); turned by 10°, 0.056; composed the wrong
//   way (−30°), 0.068; the 0° frame, ~0.08. At 4 traces a pixel the noise is 0.022 an image: a
//   bound of 0.061 that would let a 10° error through.
TEST(RenderSweepCli, TracedStageSweepMatchesSeparateRenders) {
  ASSERT_TRUE(fs::exists(kRenderBinary)) << kRenderBinary << " not built";
  const std::string d = fresh_dir("traced");
  const std::string args = kSection + kSmall + " --set render.spp=16";
  const auto t0 = std::chrono::steady_clock::now();
  const pmsim::test::CliRun r =
      run_render_cli(args + " --sweep stage_deg=0:30:30 --out " + d + "/st_%d.exr --stats " + d + "/s.json", d);
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_EQ(run_render_cli(args + " --set stage_deg=30 --out " + d + "/s30.exr", d).code, 0);
  std::printf("traced sweep and a render: %.2f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  const nlohmann::json s = read_json(d + "/s.json");
  ASSERT_TRUE(s["response"].is_object());  // one response, composed twice
  EXPECT_EQ(s["response"]["coverage"], "disc");
  EXPECT_EQ(s["frames"].size(), 2u);
  EXPECT_EQ(s["stopped"], s["response"]["stopped"]);
  auto mean_abs = [](const pmsim::LoadedImage& a, const pmsim::LoadedImage& b, double* mean_level) {
    double sum = 0.0, level = 0.0;
    std::size_t n = 0;
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        for (int c = 0; c < 3; ++c) {
          const std::size_t i = (static_cast<std::size_t>(y) * a.width + x) * a.channels + c;
          sum += std::abs(a.pixels[i] - b.pixels[i]);
          level += 0.5 * (a.pixels[i] + b.pixels[i]);
          ++n;
        }
    *mean_level = level / n;
    return sum / n;
  };
  const pmsim::LoadedImage f0 = pmsim::read_image(d + "/st_0.exr"), f1 = pmsim::read_image(d + "/st_1.exr");
  const pmsim::LoadedImage s30 = pmsim::read_image(d + "/s30.exr");
  ASSERT_EQ(f1.pixels.size(), s30.pixels.size());
  ASSERT_EQ(f0.pixels.size(), s30.pixels.size());
  EXPECT_EQ(f1.metadata["pmsim:scene"], s30.metadata["pmsim:scene"]);
  double level = 0, other = 0;
  const double d30 = mean_abs(f1, s30, &level), wrong = mean_abs(f0, s30, &other);
  std::printf("mean |Δ| linear at 30°: %.4f (level %.4f); the 0° frame against it: %.4f\n", d30, level, wrong);
  EXPECT_LT(d30, 0.039);
  EXPECT_GT(wrong, 0.039);  // the bound tells the angles apart
}

// A flat section with the gypsum plate in (optics.relief off): one flat response, each frame the
// canvas's units evaluated in the frame's train (core/specimen/figure_response.h). The 30° frame
// against a 4×-finer separate render at 30° box-filtered to 32² (what the composition's 4×-finer
// canvas holds), in mean |Δ| of linear RGB (level ~0.3): measured 0.0096 (a separate 32² render
// is 0.0256 from it: its pixels sample the grain boundaries at their centres, the canvas at 16
// points); the bound 0.02 is twice the measured, and the 0° frame (the grains turned back by 30°)
// lies ~0.2 away.
TEST(RenderSweepCli, FlatSectionWithTheGypsumPlateIsComposedFromOneResponse) {
  ASSERT_TRUE(fs::exists(kRenderBinary)) << kRenderBinary << " not built";
  const std::string d = fresh_dir("flat_gypsum");
  const std::string args = kSection + " --set optics.relief=off --set compensator=gypsum";
  const pmsim::test::CliRun r = run_render_cli(
      args + kSmall + " --sweep stage_deg=0:30:30 --out " + d + "/st_%d.exr --stats " + d + "/s.json", d);
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_EQ(run_render_cli(args + " --set render.width=128 --set render.height=128 --set stage_deg=30 --out " + d +
                               "/fine30.exr",
                           d)
                .code,
            0);
  const nlohmann::json s = read_json(d + "/s.json");
  ASSERT_TRUE(s["response"].is_object());
  EXPECT_EQ(s["response"]["coverage"], "flat");
  EXPECT_EQ(s["frames"].size(), 2u);
  const pmsim::LoadedImage f0 = pmsim::read_image(d + "/st_0.exr"), f1 = pmsim::read_image(d + "/st_1.exr");
  const pmsim::LoadedImage fine = pmsim::read_image(d + "/fine30.exr");
  ASSERT_EQ(f1.width, 32);
  ASSERT_EQ(fine.width, 128);
  ASSERT_EQ(f0.pixels.size(), f1.pixels.size());
  const auto from_fine = [&](const pmsim::LoadedImage& a) {  // mean |a − fine box-filtered 4 × 4|
    double sum = 0.0;
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        for (int c = 0; c < 3; ++c) {
          double v = 0.0;
          for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i)
              v += fine.pixels[(static_cast<std::size_t>(4 * y + j) * fine.width + 4 * x + i) * fine.channels + c];
          sum += std::abs(a.pixels[(static_cast<std::size_t>(y) * a.width + x) * a.channels + c] - v / 16.0);
        }
    return sum / (3.0 * a.width * a.height);
  };
  const double d30 = from_fine(f1), wrong = from_fine(f0);
  std::printf("mean |Δ| linear at 30° against the 4×-finer render: %.4f; the 0° frame: %.4f\n", d30, wrong);
  EXPECT_LT(d30, 0.02);
  EXPECT_GT(wrong, 0.1);
}

// A conoscopic figure's sweep is composed from its nine probes (core/specimen/figure_response.h):
// at stage 0° the composition is the separate render to float rounding (≤ 2.4·10⁻⁷ in XYZ,
// tests/figure_response_test.cpp), so the 8-bit frames differ from the separate renders by at
// most one level where a value sits on a rounding edge.
TEST(RenderSweepCli, FigureSweepIsComposedFromOneResponse) {
  ASSERT_TRUE(fs::exists(kRenderBinary)) << kRenderBinary << " not built";
  const std::string d = fresh_dir("figure");
  const std::string figure = std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/biaxial_acute_bisectrix.json" + kSmall;
  const pmsim::test::CliRun r =
      run_render_cli(figure + " --sweep analyzer_deg=0:90:45 --out " + d + "/a_%d.png --stats " + d + "/s.json", d);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json s = read_json(d + "/s.json");
  ASSERT_TRUE(s["response"].is_object());
  EXPECT_EQ(s["response"]["coverage"], "figure");
  EXPECT_EQ(s["stopped"], s["response"]["stopped"]);
  const char* values[] = {"0", "45", "90"};
  for (int i = 0; i < 3; ++i) {
    const std::string single = d + "/single_" + values[i] + ".png";
    ASSERT_EQ(run_render_cli(figure + " --set analyzer_deg=" + values[i] + " --out " + single, d).code, 0);
    const pmsim::LoadedImage a = pmsim::read_image(d + "/a_" + std::to_string(i) + ".png"), b = pmsim::read_image(single);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < a.pixels.size(); ++k) worst = std::max(worst, std::abs(double(a.pixels[k]) - b.pixels[k]));
    EXPECT_LE(worst, 1.0 / 255.0 + 1e-6) << "frame " << i << " against --set analyzer_deg=" << values[i];
  }
  // Parallel and crossed analyzers differ: the frames are not one image repeated.
  EXPECT_FALSE(pmsim::read_image(d + "/a_0.png").pixels == pmsim::read_image(d + "/a_2.png").pixels);
}
