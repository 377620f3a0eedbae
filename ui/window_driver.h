#pragma once
// The desktop window: GLFW + OpenGL 3.3 core + ImGui's GLFW and OpenGL3 backends.
#include <memory>
#include <string>

#include "ui/ui_driver.h"

struct GLFWwindow;

namespace pmsim::ui {

class WindowDriver : public UiDriver {
 public:
  // Null with the reason in `log` when there is no display or no 3.3 core context.
  static std::unique_ptr<WindowDriver> create(const Scene& scene, int width, int height, std::string& log,
                                              int renderer_threads = 0);
  ~WindowDriver() override;
  const char* gl_name() const override { return "GLFW window"; }
  WindowPixels read_pixels() override;

 protected:
  bool begin_frame() override;
  void bind_target() override;
  void end_frame() override;
  void framebuffer_size(int& w, int& h) const override { w = fb_width_, h = fb_height_; }

 private:
  WindowDriver() = default;
  GLFWwindow* window_ = nullptr;
  int fb_width_ = 0, fb_height_ = 0;
  float content_scale_ = 1.0f;  // as last reported to the app
};

}  // namespace pmsim::ui
