// Opaque grains (issue 22, "opaque grains dark in plane and crossed light"): the basalt's
// magnetite, rendered by pmsim-render at 10× in plane light and between crossed polars, is black
// beside the field's mean, and --grains reports it as opaque with no extinction or interference
// colour to read.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "core/io/image_file.h"
#include "tests/reliability_support.h"

using namespace pmsim;
using namespace pmsim::reliability;

namespace {

const std::string kRender = std::string(PMSIM_BINARY_DIR) + "/app/pmsim-render";
const std::string kScene = std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/basalt_section_ortho.json";
// 10×: a 2 mm field, 128 px of 16 µm: the grown basalt's 0.03–0.25 mm magnetite grains are 2–15 px
// across, so some of their pixels have all four neighbours in the same grain (no boundary mixing).
constexpr int kSize = 128;

struct Render {
  LoadedImage image;
  std::vector<std::uint16_t> labels;
  nlohmann::json grains;
};

Render render(const ScratchDir& dir, const std::vector<std::string>& extra) {
  std::vector<std::string> a = {kRender, kScene,
                                "--set", "render.width=" + std::to_string(kSize),
                                "--set", "render.height=" + std::to_string(kSize),
                                "--set", "render.spp=1",
                                "--set", "render.wavelengths=16",
                                "--out", dir / "a.exr", "--labels", dir / "l.png", "--grains", dir / "g.json"};
  a.insert(a.end(), extra.begin(), extra.end());
  const CommandResult r = run_command(a, dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  Render out;
  out.image = read_image(dir / "a.exr");
  const LoadedImage l = read_image(dir / "l.png");
  for (float v : l.pixels) out.labels.push_back(static_cast<std::uint16_t>(std::lround(v * 65535.0f)));
  out.grains = nlohmann::json::parse(read_file(dir / "g.json"));
  return out;
}

double luminance(const LoadedImage& img, std::size_t i) {  // Rec. 709 Y of linear RGB
  return 0.2126 * img.pixels[3 * i] + 0.7152 * img.pixels[3 * i + 1] + 0.0722 * img.pixels[3 * i + 2];
}

struct Means {
  double opaque = 0.0, field = 0.0;
  int opaque_px = 0;
};

// Mean luminance of the opaque grains' interior pixels (all 4-neighbours in the same grain) and of
// the whole field.
Means means(const Render& r, const std::set<std::uint16_t>& opaque) {
  Means m;
  double sum = 0.0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const std::size_t i = std::size_t(y) * kSize + std::size_t(x);
      m.field += luminance(r.image, i);
      const std::uint16_t k = r.labels[i];
      if (!opaque.count(k) || x == 0 || y == 0 || x + 1 == kSize || y + 1 == kSize) continue;
      if (r.labels[i - 1] != k || r.labels[i + 1] != k || r.labels[i - kSize] != k || r.labels[i + kSize] != k) continue;
      sum += luminance(r.image, i);
      ++m.opaque_px;
    }
  m.field /= double(kSize * kSize);
  m.opaque = m.opaque_px ? sum / m.opaque_px : 0.0;
  return m;
}

}  // namespace

TEST(OpaqueGrains, MagnetiteIsDarkInPlaneAndCrossedLight) {
  ScratchDir dir;
  // The traced slab (the default: relief, Becke lines) in both lights, and the flat model.
  const Render crossed = render(dir, {});
  const Render plane = render(dir, {"--set", "analyzer=out"});
  const Render flat = render(dir, {"--set", "optics.relief=off"});
  std::set<std::uint16_t> magnetite;
  for (const auto& g : crossed.grains["grains"]) {
    const bool opaque = g.at("opaque").get<bool>();
    EXPECT_EQ(opaque, g["mineral"] == "magnetite") << g.dump();
    if (!opaque) continue;
    magnetite.insert(g["id"].get<std::uint16_t>());
    // Nothing of the optics is observable: no extinction, slow direction or interference colour.
    EXPECT_TRUE(g["extinction_stage_deg"].empty()) << g.dump();
    EXPECT_TRUE(g["extinction_angle_deg"].is_null()) << g.dump();
    EXPECT_EQ(g["retardation_nm"].get<double>(), 0.0);
    EXPECT_FALSE(g.contains("brightness_test")) << g.dump();
  }
  ASSERT_GE(magnetite.size(), 5u) << "the 10× field should hold several magnetite grains";
  for (const Render* r : {&crossed, &plane, &flat}) {
    const Means m = means(*r, magnetite);
    const std::string light = r == &crossed ? "crossed" : r == &plane ? "plane" : "crossed_flat";
    ASSERT_GE(m.opaque_px, 20) << light;
    // The grains pass exactly nothing (crystal_opaque_test); what an interior pixel may still show
    // is the traced image's blur of the neighbours' light across grains a few pixels wide. Dark:
    // under 1 % of the field's mean. Measured on the grown basalt: 0.43 % between crossed polars
    // (traced; 8.95e-4 against 0.207), 0.58 % in plane light (5.2e-3 against 0.892), 0 in the
    // flat model (the hand-placed basalt's larger, rounder grains: 0.3 %, 3e-7 of the field, 0).
    EXPECT_LT(m.opaque, 0.01 * m.field) << light << ": magnetite " << m.opaque << " against the field's "
                                        << m.field << " over " << m.opaque_px << " px";
    RecordProperty(light + "_magnetite", std::to_string(m.opaque));
    RecordProperty(light + "_field", std::to_string(m.field));
    std::printf("%s: magnetite %.3g over %d px, field %.4g\n", light.c_str(), m.opaque, m.opaque_px, m.field);
  }
}
