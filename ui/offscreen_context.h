#pragma once
// An OpenGL 3.3 core context with no window, rendering into a framebuffer object of a fixed size:
// EGL on Mesa's surfaceless platform, or OSMesa when EGL is not usable. `pmsim --headless` draws
// the whole UI into it and reads the pixels back.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ui/gl_functions.h"
#include "ui/imgui_gl_backend.h"

namespace pmsim::ui {

enum class OffscreenApi { EglSurfaceless, OSMesa };

class OffscreenContext {
 public:
  // Tries EGL surfaceless, then OSMesa. Environment variable PMSIM_GL=egl|osmesa forces one.
  // Returns null (with the reasons in `log`) if neither works. Makes the context current, loads
  // gl() and binds the framebuffer object.
  static std::unique_ptr<OffscreenContext> create(int width, int height, std::string& log);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  OffscreenApi api() const { return api_; }
  const char* api_name() const;
  int width() const { return width_; }
  int height() const { return height_; }
  const ImGuiGlBackend& imgui_backend() const { return backend_; }
  void bind_framebuffer();
  // The framebuffer as 8-bit RGB, top row first.
  std::vector<std::uint8_t> read_rgb8();

 private:
  OffscreenContext() = default;
  bool create_framebuffer(std::string& log);
  bool try_egl(std::string& log);
  bool try_osmesa(std::string& log);

  OffscreenApi api_ = OffscreenApi::EglSurfaceless;
  int width_ = 0, height_ = 0;
  ImGuiGlBackend backend_;
  unsigned fbo_ = 0, color_ = 0;
  void* egl_display_ = nullptr;
  void* egl_context_ = nullptr;
  void* osmesa_context_ = nullptr;
  std::vector<std::uint8_t> osmesa_buffer_;
};

}  // namespace pmsim::ui
