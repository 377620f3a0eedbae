#pragma once
// The whole window drawn off-screen (EGL surfaceless, else OSMesa) at a fixed size: what
// `pmsim --headless` and the UI tests run.
#include <memory>
#include <string>

#include "ui/offscreen_context.h"
#include "ui/ui_driver.h"

namespace pmsim::ui {

class HeadlessDriver : public UiDriver {
 public:
  // Null with the reasons in `log` if no off-screen GL context can be made.
  static std::unique_ptr<HeadlessDriver> create(const Scene& scene, int width, int height, std::string& log,
                                                int renderer_threads = 0);
  ~HeadlessDriver() override;
  const char* gl_name() const override { return context_->api_name(); }
  WindowPixels read_pixels() override { return {width_, height_, context_->read_rgb8()}; }

 protected:
  bool begin_frame() override;
  void bind_target() override { context_->bind_framebuffer(); }
  void end_frame() override;

 private:
  HeadlessDriver() = default;
  std::unique_ptr<OffscreenContext> context_;
  double last_time_s_ = 0;
};

}  // namespace pmsim::ui
