#pragma once
// Where everything sits in the window. Fixed, computed from the window size (no imgui.ini), so
// that screenshots are reproducible and tests know where the field of view is.
namespace pmsim::ui {

struct Rect {
  float x = 0, y = 0, w = 0, h = 0;
  bool contains(float px, float py) const { return px >= x && py >= y && px < x + w && py < y + h; }
  float cx() const { return x + w / 2; }
  float cy() const { return y + h / 2; }
};

struct Layout {
  Rect controls;  // left: microscope controls
  Rect view;      // centre: the field window
  Rect field;     // the square the field image fills (a circular field stop inscribed in it)
  Rect status;    // under the field: samples, error, frame time
  Rect chart;     // under the status line: the Michel-Lévy chart
  Rect teaching;  // right: cursor probe, figure description, shortcuts
  float field_radius() const { return field.w / 2; }
};

// `ui_scale` (ui_scale.h) widens the side panels and the status line with the text they hold.
Layout compute_layout(int window_width, int window_height, float ui_scale = 1.0f);

// Background colours (sRGB-encoded, as ImGui colours are). The drivers clear the framebuffer to
// them and the windows draw no background of their own: with software OpenGL a clear is a
// memset, a window background is a blended quad over a million pixels.
constexpr float kPanelBackground[3] = {0.06f, 0.06f, 0.06f};
constexpr float kViewBackground[3] = {0.22f, 0.22f, 0.23f};

}  // namespace pmsim::ui
