// Image files: formats, metadata, and atomic writes that never leave half-written files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/io/atomic_file.h"
#include "core/io/image_file.h"
#include "core/spectrum/color.h"

using namespace pmsim;

namespace {
std::string temp_dir() {
  const auto d = std::filesystem::temp_directory_path() / ("pmsim_img_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d.string();
}
std::string read_all(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}
std::size_t files_in(const std::string& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}
}  // namespace

TEST(ImageFile, ExrKeepsLinearFloatsAndTheSceneMetadata) {
  const std::string path = temp_dir() + "/a.exr";
  const std::vector<float> rgb = {0.0f, 0.5f, 2.0f, 1e-4f, 0.25f, 0.75f};
  const nlohmann::json meta = {{"stage_deg", 45.0}, {"sample", {{"mineral", "quartz"}}}};
  write_image(path, 2, 1, rgb, meta);
  const LoadedImage img = read_image(path);
  ASSERT_EQ(img.width, 2);
  ASSERT_EQ(img.channels, 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) EXPECT_FLOAT_EQ(img.pixels[i], rgb[i]);
  EXPECT_EQ(img.metadata["pmsim:scene"], meta);
}

TEST(ImageFile, PngIsSrgbEncodedAndClippedPerChannel) {
  const std::string path = temp_dir() + "/a.png";
  // Out of gamut: negative and > 1 clip per channel in linear RGB before encoding.
  const std::vector<float> rgb = {-0.2f, 0.5f, 1.7f};
  write_image(path, 1, 1, rgb, nlohmann::json::object());
  const LoadedImage img = read_image(path);
  ASSERT_EQ(img.channels, 3);
  EXPECT_FLOAT_EQ(img.pixels[0], 0.0f);
  // sRGB encode(0.5) = 0.7354 → 188/255 (IEC 61966-2-1).
  EXPECT_NEAR(img.pixels[1], 188.0 / 255.0, 1e-6);
  EXPECT_FLOAT_EQ(img.pixels[2], 1.0f);
  EXPECT_TRUE(img.metadata["pmsim:scene"].is_object());
}

TEST(ImageFile, TiffIsFloat) {
  const std::string path = temp_dir() + "/a.tif";
  write_image(path, 1, 1, {0.125f, 3.0f, 0.0f}, nlohmann::json{{"k", 1}});
  const LoadedImage img = read_image(path);
  EXPECT_FLOAT_EQ(img.pixels[1], 3.0f);
  EXPECT_EQ(img.metadata["pmsim:scene"]["k"], 1);
}

TEST(AtomicFile, FailedWriteLeavesTheOldFileAndNoTemporary) {
  const std::string dir = temp_dir() + "/atomic";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/keep.txt";
  write_text_atomically(path, "old");
  EXPECT_THROW(write_atomically(path,
                                [](const std::string& tmp) {
                                  std::ofstream(tmp) << "half";
                                  throw std::runtime_error("disk full");
                                }),
               std::runtime_error);
  EXPECT_EQ(read_all(path), "old");
  EXPECT_EQ(files_in(dir), 1u);  // the temporary is gone
}

TEST(AtomicFile, UnwritableFolderIsAnErrorNamingThePath) {
  const std::string path = "/nonexistent_folder_pmsim/out.png";
  try {
    write_image(path, 1, 1, {0.f, 0.f, 0.f}, nlohmann::json::object());
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(AtomicFile, UnknownExtensionIsRejectedBeforeAnythingIsWritten) {
  const std::string dir = temp_dir() + "/ext";
  std::filesystem::create_directories(dir);
  EXPECT_THROW(write_image(dir + "/a.bmpx", 1, 1, {0.f, 0.f, 0.f}, nullptr), std::runtime_error);
  EXPECT_EQ(files_in(dir), 0u);
}
