#include "ui/headless_driver.h"

#include <chrono>

#include <imgui.h>

namespace pmsim::ui {
namespace {
double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

std::unique_ptr<HeadlessDriver> HeadlessDriver::create(const Scene& scene, int width, int height,
                                                       std::string& log, int renderer_threads) {
  std::unique_ptr<HeadlessDriver> d(new HeadlessDriver());
  d->width_ = width;
  d->height_ = height;
  d->context_ = OffscreenContext::create(width, height, log);
  if (!d->context_) return nullptr;
  if (!d->init_imgui(d->context_->imgui_backend(), scene, renderer_threads, log)) return nullptr;
  d->last_time_s_ = now_s();
  return d;
}

HeadlessDriver::~HeadlessDriver() { shutdown_imgui(); }

bool HeadlessDriver::begin_frame() {
  backend_.new_frame();
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width_), static_cast<float>(height_));
  io.DisplayFramebufferScale = ImVec2(1, 1);
  const double t = now_s();
  io.DeltaTime = static_cast<float>(std::max(t - last_time_s_, 1e-4));
  last_time_s_ = t;
  return true;
}

// Software GL queues work; finishing here makes the frame time the real cost of the pixels.
void HeadlessDriver::end_frame() { gl().Finish(); }

}  // namespace pmsim::ui
