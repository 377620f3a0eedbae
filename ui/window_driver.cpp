#include "ui/window_driver.h"

#include <cstring>
#include <string>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui.h>

#include "core/base/version.h"
#include "ui/gl_functions.h"

namespace pmsim::ui {
namespace {
GlProc glfw_proc(const char* name) { return glfwGetProcAddress(name); }
std::string glfw_error() {
  const char* text = nullptr;
  glfwGetError(&text);
  return text ? text : "unknown GLFW error";
}
}  // namespace

std::unique_ptr<WindowDriver> WindowDriver::create(const Scene& scene, int width, int height,
                                                   std::string& log, int renderer_threads) {
  if (!glfwInit()) {
    log += "GLFW: " + glfw_error() + "\n";
    return nullptr;
  }
  std::unique_ptr<WindowDriver> d(new WindowDriver());
  d->width_ = width;
  d->height_ = height;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  d->window_ = glfwCreateWindow(width, height, (pmsim_software_name() + " - polarizing microscope").c_str(),
                               nullptr, nullptr);
  if (!d->window_) {
    log += "GLFW: cannot open a window with OpenGL 3.3 core: " + glfw_error() + "\n";
    return nullptr;
  }
  glfwMakeContextCurrent(d->window_);
  glfwSwapInterval(1);
  const char* missing = nullptr;
  if (!gl().load(glfw_proc, &missing)) {
    log += std::string("GLFW: missing GL entry point ") + missing + "\n";
    return nullptr;
  }
  d->imgui_ = nullptr;
  // The GLFW backend installs its callbacks; the ImGui context must exist first.
  IMGUI_CHECKVERSION();
  if (!d->init_imgui(prebuilt_imgui_gl_backend(), scene, renderer_threads, log)) return nullptr;
  ImGui_ImplGlfw_InitForOpenGL(d->window_, true);
  return d;
}

WindowDriver::~WindowDriver() {
  if (imgui_) {
    ImGui::SetCurrentContext(imgui_);
    ImGui_ImplGlfw_Shutdown();
  }
  shutdown_imgui();
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

bool WindowDriver::begin_frame() {
  glfwPollEvents();
  if (glfwWindowShouldClose(window_)) return false;
  glfwGetFramebufferSize(window_, &fb_width_, &fb_height_);
  // The monitor's content scale (HiDPI, a projector's setting), what ui.scale=auto follows; it
  // changes when the window moves to another monitor.
  float xs = 1.0f, ys = 1.0f;
  glfwGetWindowContentScale(window_, &xs, &ys);
  if (xs > 0.0f && xs != content_scale_) {
    content_scale_ = xs;
    app_->set_content_scale(xs);
  }
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  if (w > 0 && h > 0 && (w != width_ || h != height_)) {
    width_ = w;
    height_ = h;
    app_->set_window_size(w, h);
  }
  backend_.new_frame();
  ImGui_ImplGlfw_NewFrame();
  return true;
}

void WindowDriver::bind_target() {
  gl().BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl().Viewport(0, 0, fb_width_, fb_height_);
}

void WindowDriver::end_frame() { glfwSwapBuffers(window_); }

WindowPixels WindowDriver::read_pixels() {
  const int w = fb_width_, h = fb_height_;
  std::vector<std::uint8_t> rgba(static_cast<size_t>(w) * h * 4);
  gl().BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl().PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl().ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  std::vector<std::uint8_t> rgb(static_cast<size_t>(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      std::memcpy(&rgb[(static_cast<size_t>(y) * w + x) * 3],
                  &rgba[(static_cast<size_t>(h - 1 - y) * w + x) * 4], 3);
  return {w, h, std::move(rgb)};
}

}  // namespace pmsim::ui
