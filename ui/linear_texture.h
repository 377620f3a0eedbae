#pragma once
// A GL texture showing a linear-sRGB float image: encoded to 8-bit sRGB on upload (clipped per
// channel in linear RGB, as the PNG writer does) so ImGui's shader draws it as a file would show.
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>

namespace pmsim::ui {

class LinearTexture {
 public:
  LinearTexture() = default;
  ~LinearTexture();
  LinearTexture(const LinearTexture&) = delete;
  LinearTexture& operator=(const LinearTexture&) = delete;

  // rgb_linear: width*height*3 floats, top row first.
  // `display`: the exposure and colour vision (display_matrix, core/render/exposure.h) applied to
  // linear RGB before the encoding.
  void upload(int width, int height, const std::vector<float>& rgb_linear, const glm::dmat3& display = glm::dmat3(1.0));
  void release();  // deletes the GL texture (call while the context is current)
  bool valid() const { return id_ != 0 && width_ > 0; }
  void* imgui_id() const { return reinterpret_cast<void*>(static_cast<std::uintptr_t>(id_)); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  unsigned id_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> staging_;
};

}  // namespace pmsim::ui
