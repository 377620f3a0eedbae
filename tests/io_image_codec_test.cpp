// The image codecs as a process sees them: PNG through libpng without mapping OpenImageIO, EXR
// through the OpenImageIO module loaded on first use, and a clear error when that module is missing.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/io/image_file.h"

namespace fs = std::filesystem;

namespace {
const std::string kRender = std::string(PMSIM_BINARY_DIR) + "/app/pmsim-render";

std::string temp_dir() {
  const auto d = fs::temp_directory_path() / ("pmsim_codec_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d.string();
}
struct ProcessResult {
  int exit_code = -1;
  std::string err;
};
// Runs pmsim-render on an 8×8 image with `env` in front; stderr is kept.
ProcessResult render(const std::string& env, const std::string& out) {
  const std::string err_file = temp_dir() + "/stderr.txt";
  const std::string cmd =
      env + " " + kRender + " --set render.width=8 --set render.height=8 --out " + out + " 2>" + err_file;
  const int status = std::system(cmd.c_str());
  std::ifstream f(err_file);
  std::stringstream s;
  s << f.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, s.str()};
}
}  // namespace

// The dynamic loader's own record (LD_DEBUG=files lists every shared object it opens) decides,
// not a timing: the PNG path must not open libOpenImageIO, the EXR path must (so the check can fail).
TEST(ImageCodec, PngRenderDoesNotLoadOpenImageIOButExrDoes) {
  ASSERT_TRUE(fs::exists(kRender)) << kRender << " not built";
  const ProcessResult png = render("LD_DEBUG=files", temp_dir() + "/a.png");
  ASSERT_EQ(png.exit_code, 0) << png.err;
  EXPECT_EQ(png.err.find("libOpenImageIO"), std::string::npos);
  EXPECT_NE(png.err.find("libpng"), std::string::npos)
      << "LD_DEBUG output missing: the check above proves nothing";
  const ProcessResult exr = render("LD_DEBUG=files", temp_dir() + "/a.exr");
  ASSERT_EQ(exr.exit_code, 0) << exr.err;
  EXPECT_NE(exr.err.find("libpmsim_oiio"), std::string::npos);
  EXPECT_NE(exr.err.find("libOpenImageIO"), std::string::npos);
}

TEST(ImageCodec, MissingModuleIsAnErrorNamingItAndLeavesNoFile) {
  const std::string out = temp_dir() + "/b.exr";
  const ProcessResult r = render("PMSIM_OIIO_PLUGIN=/nonexistent/libpmsim_oiio.so", out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("/nonexistent/libpmsim_oiio.so"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(temp_dir()))
    EXPECT_EQ(e.path().filename().string().find(".b.tmp"), std::string::npos)
        << "temporary left: " << e.path();
  // A PNG needs no module at all.
  EXPECT_EQ(render("PMSIM_OIIO_PLUGIN=/nonexistent/libpmsim_oiio.so", temp_dir() + "/b.png").exit_code, 0);
}

TEST(ImageCodec, PngWrittenByLibpngReadsBackWithItsSceneMetadata) {
  const std::string path = temp_dir() + "/meta.png";
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
