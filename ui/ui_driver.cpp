#include "ui/ui_driver.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <numeric>

#include <imgui.h>

#include "ui/gl_functions.h"

#include <GLFW/glfw3.h>

namespace pmsim::ui {

double FrameTimes::mean_ms() const {
  return ms.empty() ? 0.0 : std::accumulate(ms.begin(), ms.end(), 0.0) / ms.size();
}

double FrameTimes::percentile_ms(double p) const {
  if (ms.empty()) return 0.0;
  std::vector<double> sorted = ms;
  std::sort(sorted.begin(), sorted.end());
  const size_t i = std::min(sorted.size() - 1, static_cast<size_t>(p * (sorted.size() - 1) + 0.5));
  return sorted[i];
}

double FrameTimes::fps() const {
  const double m = mean_ms();
  return m > 0 ? 1000.0 / m : 0.0;
}

void setup_imgui_style() {
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.Colors[ImGuiCol_WindowBg].w = 0.0f;  // the drivers clear to the panel colour instead
  style.WindowRounding = 0;
  style.FrameRounding = 2;
  style.ItemSpacing = ImVec2(6, 5);
  ImGuiIO& io = ImGui::GetIO();
  const char* font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  std::error_code ec;
  // Latin-1, Greek, punctuation, arrows and maths: the core's texts use Γ, µ, °, →, ⟂.
  static const ImWchar ranges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2010, 0x205E, 0x2190,
                                   0x21FF, 0x2200, 0x22FF, 0x27C0, 0x27EF, 0};
  if (std::filesystem::exists(font, ec))
    io.Fonts->AddFontFromFileTTF(font, 14.0f, nullptr, ranges);
  else
    io.Fonts->AddFontDefault();
}

bool UiDriver::init_imgui(const ImGuiGlBackend& backend, const Scene& scene, int renderer_threads,
                          std::string& log) {
  IMGUI_CHECKVERSION();
  imgui_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(imgui_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the layout is computed, never restored from disk
  io.LogFilename = nullptr;
  // ImGui 1.86 reads keys through io.KeyMap; the GLFW backend fills it for a window, and the same
  // GLFW codes serve here so that an injected Enter, Escape or Tab edits text fields off-screen as
  // it does in a window (the GLFW backend's own init writes the same values again).
  for (const auto& [imgui_key, glfw_key] :
       {std::pair{ImGuiKey_Tab, GLFW_KEY_TAB}, {ImGuiKey_LeftArrow, GLFW_KEY_LEFT},
        {ImGuiKey_RightArrow, GLFW_KEY_RIGHT}, {ImGuiKey_UpArrow, GLFW_KEY_UP}, {ImGuiKey_DownArrow, GLFW_KEY_DOWN},
        {ImGuiKey_PageUp, GLFW_KEY_PAGE_UP}, {ImGuiKey_PageDown, GLFW_KEY_PAGE_DOWN}, {ImGuiKey_Home, GLFW_KEY_HOME},
        {ImGuiKey_End, GLFW_KEY_END}, {ImGuiKey_Delete, GLFW_KEY_DELETE}, {ImGuiKey_Backspace, GLFW_KEY_BACKSPACE},
        {ImGuiKey_Space, GLFW_KEY_SPACE}, {ImGuiKey_Enter, GLFW_KEY_ENTER}, {ImGuiKey_Escape, GLFW_KEY_ESCAPE},
        {ImGuiKey_KeyPadEnter, GLFW_KEY_KP_ENTER}, {ImGuiKey_A, GLFW_KEY_A}, {ImGuiKey_C, GLFW_KEY_C},
        {ImGuiKey_V, GLFW_KEY_V}, {ImGuiKey_X, GLFW_KEY_X}, {ImGuiKey_Y, GLFW_KEY_Y}, {ImGuiKey_Z, GLFW_KEY_Z}})
    io.KeyMap[imgui_key] = glfw_key;
  setup_imgui_style();
  backend_ = backend;
  if (!backend_.init || !backend_.init("#version 330 core")) {
    log += "ImGui OpenGL3 backend failed to initialise\n";
    return false;
  }
  app_ = std::make_unique<App>(scene, renderer_threads);
  app_->set_window_size(width_, height_);
  return true;
}

void UiDriver::shutdown_imgui() {
  if (!imgui_) return;
  ImGui::SetCurrentContext(imgui_);
  app_.reset();  // its textures go while the GL context is still current
  if (backend_.shutdown) backend_.shutdown();
  ImGui::DestroyContext(imgui_);
  imgui_ = nullptr;
}

UiDriver::~UiDriver() = default;

void UiDriver::inject_mouse(float x, float y, bool left_down, bool right_down) {
  mouse_injected_ = true;
  mouse_x_ = x;
  mouse_y_ = y;
  mouse_down_ = left_down;
  mouse_right_down_ = right_down;
}

void UiDriver::release_mouse() { mouse_injected_ = false; }

void UiDriver::inject_key(int glfw_key, bool shift, bool ctrl) {
  keys_pending_.push_back(glfw_key);
  mods_pending_shift_ = shift;
  mods_pending_ctrl_ = ctrl;
}

void UiDriver::inject_text(const std::string& utf8) { text_pending_ += utf8; }

void UiDriver::inject_wheel(float notches, bool ctrl) {
  wheel_pending_ += notches;
  wheel_ctrl_pending_ = ctrl;
}

void UiDriver::apply_injected_input() {
  ImGuiIO& io = ImGui::GetIO();
  if (mouse_injected_) {
    io.MousePos = ImVec2(mouse_x_, mouse_y_);
    io.MouseDown[0] = mouse_down_;
    io.MouseDown[1] = mouse_right_down_;
  }
  // Keys pressed last frame are released now (a press is one frame down, as a quick tap).
  for (int k : keys_down_) io.KeysDown[k] = false;
  if (!keys_down_.empty()) io.KeyShift = io.KeyCtrl = false;
  keys_down_.clear();
  if (!keys_pending_.empty()) {
    for (int k : keys_pending_) io.KeysDown[k] = true;
    io.KeyShift = mods_pending_shift_;
    io.KeyCtrl = mods_pending_ctrl_;
    keys_down_.swap(keys_pending_);
    keys_pending_.clear();
  }
  // A wheel turn lasts one frame, as ImGui clears io.MouseWheel after each; so does its Ctrl.
  if (wheel_ctrl_down_) io.KeyCtrl = false, wheel_ctrl_down_ = false;
  if (wheel_pending_ != 0.0f) {
    io.MouseWheel += wheel_pending_;
    if (wheel_ctrl_pending_) io.KeyCtrl = true, wheel_ctrl_down_ = true;
    wheel_pending_ = 0.0f;
    wheel_ctrl_pending_ = false;
  }
  if (!text_pending_.empty()) {
    io.AddInputCharactersUTF8(text_pending_.c_str());
    text_pending_.clear();
  }
}

void UiDriver::clear_background() {
  GlFunctions& g = gl();
  int fb_w = width_, fb_h = height_;
  framebuffer_size(fb_w, fb_h);
  g.ClearColor(kPanelBackground[0], kPanelBackground[1], kPanelBackground[2], 1.0f);
  g.Clear(GL_COLOR_BUFFER_BIT);
  const Rect& v = app_->layout().view;
  const double sx = static_cast<double>(fb_w) / width_, sy = static_cast<double>(fb_h) / height_;
  g.Enable(GL_SCISSOR_TEST);
  g.Scissor(static_cast<int>(v.x * sx), static_cast<int>(fb_h - (v.y + v.h) * sy),
            static_cast<int>(v.w * sx + 0.5), static_cast<int>(v.h * sy + 0.5));
  g.ClearColor(kViewBackground[0], kViewBackground[1], kViewBackground[2], 1.0f);
  g.Clear(GL_COLOR_BUFFER_BIT);
  g.Disable(GL_SCISSOR_TEST);
}

bool UiDriver::frame() {
  const auto t0 = std::chrono::steady_clock::now();
  ImGui::SetCurrentContext(imgui_);
  if (!begin_frame()) return false;
  apply_injected_input();
  ImGui::NewFrame();
  app_->frame();
  ImGui::Render();
  bind_target();
  clear_background();
  backend_.render(ImGui::GetDrawData());
  if (auto path = app_->take_window_screenshot_request()) {
    const WindowPixels px = read_pixels();
    app_->write_window_pixels(*path, px.width, px.height, px.rgb);
  }
  end_frame();
  if (times_.ms.size() >= 100000)  // bounded, so a long session's memory stays flat
    times_.ms.erase(times_.ms.begin(), times_.ms.begin() + 50000);
  times_.ms.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  // Smoothed over the last frames for the status line.
  const size_t n = std::min<size_t>(times_.ms.size(), 30);
  double sum = 0;
  for (size_t i = times_.ms.size() - n; i < times_.ms.size(); ++i) sum += times_.ms[i];
  app_->set_measured_fps(sum > 0 ? 1000.0 * n / sum : 0.0);
  return true;
}

}  // namespace pmsim::ui
