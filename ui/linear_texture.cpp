#include "ui/linear_texture.h"

#include <array>
#include <cmath>

#include "core/spectrum/color.h"
#include "ui/gl_functions.h"

namespace pmsim::ui {
namespace {

// 8-bit sRGB of linear values on a fine grid: the exact transfer function per pixel would cost a
// pow() per channel on the UI thread; 1/16384 steps stay below half an 8-bit level everywhere.
constexpr int kLutSize = 16384;
const std::array<std::uint8_t, kLutSize + 1>& srgb_lut() {
  static const auto lut = [] {
    std::array<std::uint8_t, kLutSize + 1> t{};
    for (int i = 0; i <= kLutSize; ++i) t[i] = linear_to_srgb8(static_cast<double>(i) / kLutSize);
    return t;
  }();
  return lut;
}

std::uint8_t encode(float v) {
  if (!(v > 0.0f)) return 0;  // also NaN
  if (v >= 1.0f) return 255;
  return srgb_lut()[static_cast<int>(v * kLutSize + 0.5f)];
}

}  // namespace

LinearTexture::~LinearTexture() { release(); }

void LinearTexture::release() {
  if (id_ && gl().DeleteTextures) gl().DeleteTextures(1, &id_);
  id_ = 0;
  width_ = height_ = 0;
}

void LinearTexture::upload(int width, int height, const std::vector<float>& rgb_linear, const glm::dmat3& display) {
  if (width <= 0 || height <= 0 || rgb_linear.size() < static_cast<size_t>(width) * height * 3) return;
  staging_.resize(static_cast<size_t>(width) * height * 4);
  // Float rows of the display matrix: m[c][r] is row r, column c (glm is column-major).
  float m[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[r][c] = static_cast<float>(display[c][r]);
  for (size_t i = 0, n = static_cast<size_t>(width) * height; i < n; ++i) {
    const float* p = &rgb_linear[3 * i];
    for (int r = 0; r < 3; ++r) staging_[4 * i + r] = encode(m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2]);
    staging_[4 * i + 3] = 255;
  }
  GlFunctions& g = gl();
  g.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (!id_) {
    g.GenTextures(1, &id_);
    g.BindTexture(GL_TEXTURE_2D, id_);
    g.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    g.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    g.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    g.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  } else {
    g.BindTexture(GL_TEXTURE_2D, id_);
  }
  if (width != width_ || height != height_) {
    g.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, staging_.data());
    width_ = width;
    height_ = height;
  } else {
    g.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, staging_.data());
  }
}

}  // namespace pmsim::ui
