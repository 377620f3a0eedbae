#include "ui/layout.h"

#include <algorithm>

namespace pmsim::ui {

Layout compute_layout(int window_width, int window_height, float ui_scale) {
  const float w = static_cast<float>(window_width), h = static_cast<float>(window_height);
  const float pad = 8;
  // Side panels take a quarter each at 1280 wide, never narrower than their widgets need.
  // Scaled with the text, but never more than 40 % of the window each.
  const float side = std::min(std::clamp(w * 0.25f, 260.0f * ui_scale, 400.0f * ui_scale), 0.4f * w);
  Layout l;
  l.controls = {0, 0, side, h};
  l.teaching = {w - side, 0, side, h};
  l.view = {side, 0, w - 2 * side, h};
  const float status_h = 48 * ui_scale, chart_h = std::clamp(h * 0.18f, 90.0f, 200.0f);
  const float field_side = std::max(64.0f, std::min(l.view.w - 2 * pad, h - status_h - chart_h - 4 * pad));
  l.field = {l.view.x + (l.view.w - field_side) / 2, pad, field_side, field_side};
  l.status = {l.view.x + pad, l.field.y + field_side + pad, l.view.w - 2 * pad, status_h};
  l.chart = {l.view.x + pad, l.status.y + status_h + pad, l.view.w - 2 * pad,
             h - (l.status.y + status_h + 2 * pad)};
  return l;
}

}  // namespace pmsim::ui
