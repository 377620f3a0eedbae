#pragma once
// 8-bit RGB and 16-bit grey PNG encoding in memory with libpng, so that writing a PNG (every
// screenshot and every default render) does not load OpenImageIO: its ~260 shared libraries cost
// most of a short process's start (issue 14: 0.27 s of an 8×8 render, 72 % of it in the dynamic loader).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pmsim {

// rgb8: width*height*3 bytes, top row first, sRGB-encoded (the file is marked sRGB). `text` goes
// into iTXt chunks (UTF-8), key first; OpenImageIO reads them back as attributes of that name.
// Throws std::runtime_error with libpng's message on failure.
std::vector<unsigned char> encode_png_rgb8(int width, int height, const std::uint8_t* rgb8,
                                           const std::vector<std::pair<std::string, std::string>>& text);

// grey16: width*height samples, top row first, written as a 16-bit greyscale PNG without colour-
// space chunks (the values are data, e.g. grain labels, not intensities). Same `text` and errors.
std::vector<unsigned char> encode_png_gray16(int width, int height, const std::uint16_t* grey16,
                                             const std::vector<std::pair<std::string, std::string>>& text);

}  // namespace pmsim
