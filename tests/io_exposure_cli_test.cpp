// render.exposure_ev through pmsim-render: an 8-bit PNG is the linear image × 2^ev before the
// sRGB encoding, up to clipping; EXR stays linear and unscaled, with the key in its metadata; an
// out-of-range value exits 2 naming key and value, and writes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/io/image_file.h"
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
