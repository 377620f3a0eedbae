// The image codecs as a process sees them: PNG through libpng without mapping OpenImageIO, EXR
// through the OpenImageIO module loaded on first use, and a clear error when that module is missing.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/io/image_file.h"
#include "tests/reliability_support.h"

namespace fs = std::filesystem;

namespace {
using pmsim::reliability::CommandResult;
using pmsim::reliability::run_command;
using pmsim::reliability::ScratchDir;

const std::string kRender = std::string(PMSIM_BINARY_DIR) + "/app/pmsim-render";

// pmsim-render on an 8×8 image into `out`, with `env` set for it; stderr is kept.
CommandResult render(const ScratchDir& scratch, const std::vector<std::string>& env, const std::string& out) {
  return run_command({kRender, "--set", "render.width=8", "--set", "render.height=8", "--out", out}, scratch,
                     env);
}
}  // namespace

// The dynamic loader's own record (LD_DEBUG=files lists every shared object it opens) decides,
// not a timing: the PNG path must not open libOpenImageIO, the EXR path must (so the check can fail).
TEST(ImageCodec, PngRenderDoesNotLoadOpenImageIOButExrDoes) {
  ASSERT_TRUE(fs::exists(kRender)) << kRender << " not built";
  ScratchDir dir;
  const CommandResult png = render(dir, {"LD_DEBUG=files"}, dir / "a.png");
  ASSERT_EQ(png.exit_code, 0) << png.err;
  EXPECT_EQ(png.err.find("libOpenImageIO"), std::string::npos);
  EXPECT_NE(png.err.find("libpng"), std::string::npos)
      << "LD_DEBUG output missing: the check above proves nothing";
  const CommandResult exr = render(dir, {"LD_DEBUG=files"}, dir / "a.exr");
  ASSERT_EQ(exr.exit_code, 0) << exr.err;
  EXPECT_NE(exr.err.find("libpmsim_oiio"), std::string::npos);
  EXPECT_NE(exr.err.find("libOpenImageIO"), std::string::npos);
}

TEST(ImageCodec, MissingModuleIsAnErrorNamingItAndLeavesNoFile) {
  ScratchDir dir;
  const std::string out = dir / "b.exr";
  const CommandResult r = render(dir, {"PMSIM_OIIO_PLUGIN=/nonexistent/libpmsim_oiio.so"}, out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("/nonexistent/libpmsim_oiio.so"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".b.tmp"), std::string::npos)
        << "temporary left: " << e.path();
  // A PNG needs no module at all.
  EXPECT_EQ(render(dir, {"PMSIM_OIIO_PLUGIN=/nonexistent/libpmsim_oiio.so"}, dir / "b.png").exit_code, 0);
}

TEST(ImageCodec, PngWrittenByLibpngReadsBackWithItsSceneMetadata) {
  ScratchDir dir;
  const std::string path = dir / "meta.png";
  const std::vector<float> rgb = {0.0f, 0.5f, 1.0f, 0.2f, 0.2f, 0.2f};
  const nlohmann::json meta = {{"sample", {{"mineral", "quartz"}, {"thickness_um", 30.0}}},
                               {"note", "µm, Δn"}};
  pmsim::write_image(path, 2, 1, rgb, meta);
  const pmsim::LoadedImage img = pmsim::read_image(path);
  ASSERT_EQ(img.width, 2);
  ASSERT_EQ(img.channels, 3);
  ASSERT_TRUE(img.metadata.contains("pmsim:scene"));
  EXPECT_EQ(img.metadata["pmsim:scene"], meta);  // UTF-8 text survives (iTXt chunks)
  // sRGB-encoded 8-bit: 0.5 linear → 188/255 (IEC 61966-2-1), read back as the encoded value.
  EXPECT_NEAR(img.pixels[1], 188.0 / 255.0, 0.5 / 255.0);
  EXPECT_EQ(img.pixels[2], 1.0f);
}
