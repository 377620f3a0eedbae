#pragma once
// Runs the App frame by frame on some GL surface: a GLFW window or an off-screen context. The
// frame reads top to bottom: events → new frame → App::frame() → render → present. Scripts and
// tests inject mouse and key input here, into the same ImGui input state the GLFW backend fills,
// so a scripted drag or key press takes exactly the path a real one takes.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ui/app.h"
#include "ui/imgui_gl_backend.h"

struct ImGuiContext;

namespace pmsim::ui {

struct WindowPixels {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // 8-bit RGB, top row first
};

struct FrameTimes {
  std::vector<double> ms;  // wall time of every frame (event handling to presented pixels)
  double mean_ms() const;
  double percentile_ms(double p) const;  // p in [0,1]
  double fps() const;                    // 1000 / mean
};

class UiDriver {
 public:
  virtual ~UiDriver();
  UiDriver(const UiDriver&) = delete;
  UiDriver& operator=(const UiDriver&) = delete;

  App& app() { return *app_; }
  int width() const { return width_; }
  int height() const { return height_; }
  virtual const char* gl_name() const = 0;

  // One whole frame; false once the user closed the window.
  bool frame();
  // The window as last drawn.
  virtual WindowPixels read_pixels() = 0;
  const FrameTimes& frame_times() const { return times_; }

  // Injected input, applied from the next frame on. A key press lasts one frame.
  void inject_mouse(float x, float y, bool left_down, bool right_down = false);
  void release_mouse();  // stop overriding the mouse (window driver: back to the real one)
  void inject_key(int glfw_key, bool shift, bool ctrl);
  void inject_text(const std::string& utf8);
  // Mouse-wheel notches (+ = away from the user) with Ctrl held or not, for one frame, at the
  // injected mouse position.
  void inject_wheel(float notches, bool ctrl);

 protected:
  UiDriver() = default;
  // Creates the ImGui context, loads the font and style, initialises the renderer backend and
  // the App. The GL context must be current.
  bool init_imgui(const ImGuiGlBackend& backend, const Scene& scene, int renderer_threads, std::string& log);
  void shutdown_imgui();
  virtual bool begin_frame() = 0;  // events, platform new frame (DisplaySize, DeltaTime)
  virtual void bind_target() = 0;  // framebuffer to draw into
  virtual void end_frame() = 0;    // swap or finish
  virtual void framebuffer_size(int& w, int& h) const { w = width_, h = height_; }

  int width_ = 0, height_ = 0;
  ImGuiGlBackend backend_;
  ImGuiContext* imgui_ = nullptr;
  std::unique_ptr<App> app_;

 private:
  void apply_injected_input();
  void clear_background();
  FrameTimes times_;
  bool mouse_injected_ = false;
  float mouse_x_ = 0, mouse_y_ = 0;
  bool mouse_down_ = false;
  bool mouse_right_down_ = false;
  std::vector<int> keys_down_;     // held during the current frame
  std::vector<int> keys_pending_;  // pressed on the next frame
  bool shift_ = false, ctrl_ = false;
  float wheel_pending_ = 0.0f;
  bool wheel_ctrl_pending_ = false, wheel_ctrl_down_ = false;
  bool mods_pending_shift_ = false, mods_pending_ctrl_ = false;
  std::string text_pending_;
};

// Applies the look shared by every driver (dark theme, DejaVu Sans when installed).
void setup_imgui_style();

}  // namespace pmsim::ui
