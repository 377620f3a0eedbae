// render.exposure_ev through pmsim-render: an 8-bit PNG is the linear image × 2^ev before the
// sRGB encoding, up to clipping; EXR stays linear and unscaled, with the key in its metadata; an
// out-of-range value exits 2 naming key and value, and writes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/glm.hpp>

#include "core/io/image_file.h"
#include "core/spectrum/colour_vision.h"
#include "render_cli_run.h"

namespace fs = std::filesystem;
using namespace pmsim;

namespace {

std::string temp_dir() { return test::cli_temp_dir("exposure_test"); }
test::CliRun run(const std::string& args) { return test::run_render_cli(args, temp_dir()); }

// The empty field (sample out, analyzer out) at one wavelength: a uniform linear value, 16×16.
const std::string kField =
    " --set sample.present=false --set analyzer=out --set render.width=16 --set render.height=16"
    " --set render.single_wavelength_nm=550 ";

// The sRGB decoding of an encoded value in 0..1 (IEC 61966-2-1).
double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

// Linear green of the centre pixel of a PNG pmsim-render wrote with render.exposure_ev = ev.
double png_centre(double ev, LoadedImage* image = nullptr) {
  const std::string out = temp_dir() + "/ev.png";
  fs::remove(out);
  const test::CliRun r = run(kField + "--set render.exposure_ev=" + std::to_string(ev) + " --out " + out);
  EXPECT_EQ(r.code, 0) << r.err;
  const LoadedImage img = read_image(out);
  if (image) *image = img;
  const std::size_t c = (std::size_t(img.height / 2) * img.width + img.width / 2) * img.channels;
  return srgb_to_linear(img.pixels[c + 1]);
}

}  // namespace

TEST(ExposureCli, PngPixelScalesByTwoToTheEvUpToClipping) {
  ASSERT_TRUE(fs::exists(test::kRenderBinary)) << test::kRenderBinary << " not built";
  const double m4 = png_centre(-4.0), m3 = png_centre(-3.0), m2 = png_centre(-2.0), m1 = png_centre(-1.0);
  std::printf("empty field, linear green at ev -4..-1: %.5f %.5f %.5f %.5f\n", m4, m3, m2, m1);
  // One 8-bit sRGB level is at most 1.3 % of a linear value above 0.04 (the curve's slope there):
  // ratios of two quantized values hold to 2 × 1.3 % ≈ 0.03.
  EXPECT_NEAR(m3 / m4, 2.0, 0.03 * 2.0);
  EXPECT_NEAR(m2 / m3, 2.0, 0.03 * 2.0);
  EXPECT_NEAR(m1 / m2, 2.0, 0.03 * 2.0);
  // The field is ~1 (white): +1 stop clips to 255 everywhere.
  LoadedImage bright;
  png_centre(1.0, &bright);
  for (const float v : bright.pixels) EXPECT_EQ(v, 1.0f);
}

TEST(ExposureCli, ExrStaysLinearAndRecordsTheExposure) {
  ASSERT_TRUE(fs::exists(test::kRenderBinary)) << test::kRenderBinary << " not built";
  const std::string a = temp_dir() + "/ev0.exr", b = temp_dir() + "/evm3.exr";
  ASSERT_EQ(run(kField + "--out " + a).code, 0);
  ASSERT_EQ(run(kField + "--set render.exposure_ev=-3 --out " + b).code, 0);
  const LoadedImage ia = read_image(a), ib = read_image(b);
  ASSERT_EQ(ia.pixels.size(), ib.pixels.size());
  for (std::size_t i = 0; i < ia.pixels.size(); ++i) ASSERT_EQ(ia.pixels[i], ib.pixels[i]) << i;
  EXPECT_EQ(ib.metadata["pmsim:scene"]["render"]["exposure_ev"], -3.0) << ib.metadata.dump();
}

TEST(ExposureCli, OutOfRangeExitsTwoNamingKeyAndValue) {
  ASSERT_TRUE(fs::exists(test::kRenderBinary)) << test::kRenderBinary << " not built";
  const std::string out = temp_dir() + "/bad.png";
  fs::remove(out);
  for (const std::string v : {"10.5", "-11", "nan"}) {
    const test::CliRun r = run(kField + "--set render.exposure_ev=" + v + " --out " + out);
    EXPECT_EQ(r.code, 2) << v;
    EXPECT_NE(r.err.find("render.exposure_ev"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(v == "nan" ? "n" : v), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << v;
  }
}

// render.vision: the PNG is Φ (core/spectrum/colour_vision.h) applied to the linear image before
// the encoding — checked pixel by pixel on a coloured plate against the normal-vision PNG, within
// two 8-bit levels' worth of linear error (each PNG is quantized once: ≤ 1.3 % of a value above
// 0.04, plus 0.002 absolute near black); a bad name exits 2 naming key and value.
TEST(ExposureCli, VisionPngIsTheMachadoMatrixOfTheNormalOne) {
  ASSERT_TRUE(fs::exists(test::kRenderBinary)) << test::kRenderBinary << " not built";
  // Quartz 40 µm, optic axis at 45° to the polars: first-order yellow (Γ ≈ 360 nm), one stop
  // down so that no channel of the normal PNG clips (Φ mixes channels: a clipped one would not
  // be Φ of the image).
  const std::string plate = " --set sample.type=plate --set sample.mineral=quartz --set sample.thickness_um=40"
                            " --set sample.optic_axis=[0.70710678,0.70710678,0] --set render.exposure_ev=-1"
                            " --set render.width=16 --set render.height=16 ";
  const std::string normal = temp_dir() + "/normal.png", deutan = temp_dir() + "/deutan.png";
  ASSERT_EQ(run(plate + "--out " + normal).code, 0);
  const test::CliRun r = run(plate + "--set render.vision=deuteranopia --out " + deutan);
  ASSERT_EQ(r.code, 0) << r.err;
  const LoadedImage a = read_image(normal), b = read_image(deutan);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(b.metadata["pmsim:scene"]["render"]["vision"], "deuteranopia");
  const glm::dmat3 phi = colour_vision_matrix(ColourVision::Deuteranopia);
  double worst = 0.0, chroma = 0.0;
  for (std::size_t i = 0; i + 2 < a.pixels.size(); i += 3) {
    const glm::dvec3 lin(srgb_to_linear(a.pixels[i]), srgb_to_linear(a.pixels[i + 1]), srgb_to_linear(a.pixels[i + 2]));
    const glm::dvec3 want = glm::clamp(phi * lin, 0.0, 1.0);
    for (int c = 0; c < 3; ++c) {
      const double got = srgb_to_linear(b.pixels[i + std::size_t(c)]);
      worst = std::max(worst, std::abs(got - want[c]) / (0.026 * std::max(want[c], 0.04) + 0.002));
    }
    chroma = std::max(chroma, std::abs(lin.x - lin.y) + std::abs(lin.y - lin.z));
  }
  EXPECT_GT(chroma, 0.05) << "the plate must be coloured for the check to mean anything";
  EXPECT_LE(worst, 1.0);
  const test::CliRun bad = run(plate + "--set render.vision=colourblind --out " + temp_dir() + "/bad.png");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("render.vision"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("colourblind"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(temp_dir() + "/bad.png"));
}
