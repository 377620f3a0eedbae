#pragma once
// Image files: PNG through libpng, EXR and TIFF (and every read) through OpenImageIO, loaded on
// first use (core/io/image_codec.h). PNG: 8-bit sRGB, out-of-gamut colours clipped per channel in
// linear RGB before encoding. EXR and TIFF: linear float RGB. Settings go into the metadata
// ("pmsim:scene" holds the scene JSON). Every write is atomic: a temporary file in the target
// folder renamed into place, so a failed write leaves any existing file intact.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pmsim {

// rgb_linear: width*height*3 floats, top row first. Throws std::runtime_error naming the path on
// an unwritable folder, a full disk or an unknown extension.
void write_image(const std::string& path, int width, int height, const std::vector<float>& rgb_linear,
                 const nlohmann::json& metadata);
// Already-encoded 8-bit RGB (e.g. a window screenshot read back from OpenGL), top row first.
void write_image_rgb8(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb8,
                      const nlohmann::json& metadata);

// A 16-bit greyscale PNG of data values (e.g. the grain labels of pmsim-render --labels), top row
// first, with the same metadata chunks; atomic like the others. The path must end in .png.
void write_gray16_png(const std::string& path, int width, int height,
                      const std::vector<std::uint16_t>& values, const nlohmann::json& metadata);

struct LoadedImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;  // as stored (PNG: encoded 0..1; EXR/TIFF: linear)
  nlohmann::json metadata;    // "pmsim:scene" parsed back when present
};
LoadedImage read_image(const std::string& path);

}  // namespace pmsim
