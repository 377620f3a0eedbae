#include "core/io/image_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/base/version.h"
#include "core/io/atomic_file.h"
#include "core/io/checked_write.h"
#include "core/io/image_codec.h"
#include "core/io/png_encoder.h"
#include "core/spectrum/color.h"

namespace pmsim {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// PNG through libpng (no OpenImageIO for the common case: see core/io/image_codec.h), with the
// text chunks OpenImageIO wrote: "pmsim:scene" and ImageDescription hold the scene JSON.
std::vector<std::pair<std::string, std::string>> png_text(const nlohmann::json& metadata) {
  std::vector<std::pair<std::string, std::string>> text = {{"Software", pmsim_software_name()}};
  if (!metadata.is_null()) {
    text.emplace_back("pmsim:scene", metadata.dump());
    text.emplace_back("ImageDescription", metadata.dump());
  }
  return text;
}

void write_png(const std::string& tmp, int width, int height, const std::uint8_t* rgb8,
               const nlohmann::json& metadata) {
  write_bytes_checked(tmp, encode_png_rgb8(width, height, rgb8, png_text(metadata)));
}

std::string metadata_text(const nlohmann::json& metadata) {
  return metadata.is_null() ? "" : metadata.dump();
}

}  // namespace

void write_image(const std::string& path, int width, int height, const std::vector<float>& rgb_linear,
                 const nlohmann::json& metadata) {
  if (width <= 0 || height <= 0 || rgb_linear.size() != static_cast<std::size_t>(width) * height * 3)
    throw std::runtime_error("cannot write " + path + ": image size does not match its pixels");
  const std::string ext = lower_extension(path);
  if (ext == ".png") {
    std::vector<std::uint8_t> rgb8(rgb_linear.size());
    for (std::size_t i = 0; i < rgb8.size(); ++i) rgb8[i] = linear_to_srgb8(rgb_linear[i]);
    write_image_rgb8(path, width, height, rgb8, metadata);
    return;
  }
  if (ext != ".exr" && ext != ".tif" && ext != ".tiff")
    throw std::runtime_error("cannot write " + path + ": unknown extension '" + ext +
                             "' (use .png, .exr or .tif)");
  // Linear float: NaN/Inf never reach a file (they would poison any downstream average).
  std::vector<float> clean(rgb_linear);
  for (float& v : clean)
    if (!std::isfinite(v)) v = 0.0f;
  write_atomically(path, [&](const std::string& tmp) {
    oiio_codec().write(tmp, width, height, true, clean.data(), metadata_text(metadata));
  });
}

void write_image_rgb8(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb8,
                      const nlohmann::json& metadata) {
  if (width <= 0 || height <= 0 || rgb8.size() != static_cast<std::size_t>(width) * height * 3)
    throw std::runtime_error("cannot write " + path + ": image size does not match its pixels");
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
    throw std::runtime_error("cannot write " + path + ": unknown extension '" + ext +
                             "' (use .png, .exr or .tif)");
  write_atomically(path, [&](const std::string& tmp) {
    if (ext == ".png")
      write_png(tmp, width, height, rgb8.data(), metadata);
    else
      oiio_codec().write(tmp, width, height, false, rgb8.data(), metadata_text(metadata));
  });
}

void write_gray16_png(const std::string& path, int width, int height,
                      const std::vector<std::uint16_t>& values, const nlohmann::json& metadata) {
  if (width <= 0 || height <= 0 || values.size() != static_cast<std::size_t>(width) * height)
    throw std::runtime_error("cannot write " + path + ": image size does not match its pixels");
  if (lower_extension(path) != ".png")
    throw std::runtime_error("cannot write " + path + ": a 16-bit grey image must be a .png");
  write_atomically(path, [&](const std::string& tmp) {
    write_bytes_checked(tmp, encode_png_gray16(width, height, values.data(), png_text(metadata)));
  });
}

LoadedImage read_image(const std::string& path) { return oiio_codec().read(path); }

}  // namespace pmsim
