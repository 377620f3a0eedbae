// Over the field of an open exercise: where each task's grain lies, and after a Check the reveal
// layer — the ground truth core computes for the scene on screen (core/exercise/reveal_geometry.h):
// grain outlines, mineral names, slow and fast vibration directions, cleavage traces and the
// indicatrix section, at the current stage angle and position. Drawn as the teaching panel draws
// its probe overlay (ui/teaching_panel.cpp): lines with a dark shadow, labels beside them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include <imgui.h>

#include "core/base/units.h"
#include "ui/app.h"
#include "ui/exercise_panel.h"

namespace pmsim::ui {
namespace {

ImU32 col(const std::array<int, 3>& c, int alpha = 255) { return IM_COL32(c[0], c[1], c[2], alpha); }

void shadowed_text(ImDrawList* draw, ImVec2 p, ImU32 colour, const char* text) {
  draw->AddText(ImVec2(p.x + 1, p.y + 1), IM_COL32(0, 0, 0, 255), text);
  draw->AddText(p, colour, text);
}

// A line through `c` at image angle `deg` (counter-clockwise from +x; screen y grows down).
void angle_line(ImDrawList* draw, ImVec2 c, double deg, float half, ImU32 colour, float width, const char* label) {
  const float dx = static_cast<float>(std::cos(radians(deg))) * half;
  const float dy = -static_cast<float>(std::sin(radians(deg))) * half;
  draw->AddLine(ImVec2(c.x - dx, c.y - dy), ImVec2(c.x + dx, c.y + dy), IM_COL32(0, 0, 0, 200), width + 2);
  draw->AddLine(ImVec2(c.x - dx, c.y - dy), ImVec2(c.x + dx, c.y + dy), colour, width);
  if (label) shadowed_text(draw, ImVec2(c.x + dx + 3, c.y + dy - 7), colour, label);
}

// The indicatrix section: an ellipse with its long axis along the slow direction. Its flattening
// is (1 − n′α/n′γ) × kIndicatrixExaggeration, else every section would look like a circle (the
// panel's legend says so).
constexpr double kIndicatrixExaggeration = 10.0;
void indicatrix_ellipse(ImDrawList* draw, ImVec2 c, const RevealGrain& g, float a) {
  if (!g.slow_vibration_deg || g.n_slow <= 0) return;
  const double flat = std::min(0.8, kIndicatrixExaggeration * (1.0 - g.n_fast / g.n_slow));
  const double b = a * (1.0 - flat), phi = radians(*g.slow_vibration_deg);
  ImVec2 pts[48];
  for (int k = 0; k < 48; ++k) {
    const double t = 2.0 * kPi * k / 48;
    const double x = a * std::cos(t), y = b * std::sin(t);
    pts[k] = ImVec2(c.x + static_cast<float>(x * std::cos(phi) - y * std::sin(phi)),
                    c.y - static_cast<float>(x * std::sin(phi) + y * std::cos(phi)));
  }
  draw->AddPolyline(pts, 48, col(kRevealIndicatrix), ImDrawFlags_Closed, 1.5f);
  char text[64];
  std::snprintf(text, sizeof text, "n\u2032\u03b3 %.4f  n\u2032\u03b1 %.4f", g.n_slow, g.n_fast);
  shadowed_text(draw, ImVec2(c.x - a, c.y + a + 2), col(kRevealIndicatrix), text);
}

}  // namespace

void App::draw_task_markers(ImDrawList* draw) const {
  // Where each task's grain is in the field now: a ring and its name (a grain off the field has
  // none; "Go to the grain" brings it under the crosshair).
  // With the reveal layer on, it names the grains itself.
  if (scene_.mode != ViewMode::Ortho || scene_.bertrand_in || exercise_->reveal) return;
  const Layout& l = layout_;
  std::set<std::pair<double, double>> done;
  for (const ExerciseTaskView& t : exercise_->tasks) {
    if (!t.stage_mm || !done.insert({(*t.stage_mm)[0], (*t.stage_mm)[1]}).second) continue;
    const auto f = image_fraction_of_section_point(scene_, (*t.stage_mm)[0], (*t.stage_mm)[1]);
    if (std::hypot(f[0] - 0.5, f[1] - 0.5) > 0.46) continue;
    const ImVec2 p(l.field.x + static_cast<float>(f[0]) * l.field.w, l.field.y + static_cast<float>(f[1]) * l.field.h);
    draw->AddCircle(p, 11, IM_COL32(0, 0, 0, 200), 24, 3.5f);
    draw->AddCircle(p, 11, IM_COL32(255, 220, 60, 255), 24, 1.5f);
    const std::string name = t.grain.empty() ? t.id : "grain " + t.grain;
    shadowed_text(draw, ImVec2(p.x + 13, p.y - 20), IM_COL32(255, 220, 60, 255), name.c_str());
  }
}

void App::draw_reveal(ImDrawList* draw) const {
  const ExerciseSession& s = *exercise_;
  if (!s.reveal || !s.geometry) return;
  const RevealGeometry& geo = *s.geometry;
  const Layout& l = layout_;
  if (!geo.figure.empty()) {
    // A crystal plate: no grains, the figure's truth in words, on a dark band across the field's top.
    const std::string text = "Ground truth: " + geo.figure;
    const float width = 0.76f * l.field.w;
    const ImVec2 at(l.field.x + 0.12f * l.field.w, l.field.y + 0.07f * l.field.h);
    const ImVec2 size = ImGui::CalcTextSize(text.c_str(), nullptr, false, width);
    draw->AddRectFilled(ImVec2(at.x - 6, at.y - 4), ImVec2(at.x + width + 6, at.y + size.y + 4), IM_COL32(0, 0, 0, 190), 4.0f);
    draw->AddText(ImGui::GetFont(), ImGui::GetFontSize(), at, IM_COL32(255, 235, 90, 255), text.c_str(), nullptr, width);
    return;
  }
  auto screen = [&](double fx, double fy) {
    return ImVec2(l.field.x + static_cast<float>(fx) * l.field.w, l.field.y + static_cast<float>(fy) * l.field.h);
  };
  auto inside = [](double fx, double fy, double r) { return std::hypot(fx - 0.5, fy - 0.5) <= r; };
  // On whole pixels (AddLine adds the half pixel to the centre): a 1 px line between two pixels
  // would be two half-bright ones.
  auto crisp = [&](double fx, double fy) {
    const ImVec2 p = screen(fx, fy);
    return ImVec2(std::floor(p.x), std::floor(p.y));
  };
  for (const RevealSegment& g : geo.outlines)
    if (inside(g.x0, g.y0, 0.5) && inside(g.x1, g.y1, 0.5))
      draw->AddLine(crisp(g.x0, g.y0), crisp(g.x1, g.y1), col(kRevealOutline), 1.0f);
  // The task grains by label (after Check the truth names them), for their names and details.
  std::map<int, std::string> task_grain;
  if (s.truth)
    for (const StudentTask& t : s.truth->tasks)
      if (t.grain_label > 0 && t.stage_mm) task_grain.emplace(t.grain_label, t.spec.grain.empty() ? t.spec.id : t.spec.grain);
  const double pixels = double(geo.width) * geo.height;
  for (const RevealGrain& g : geo.grains) {
    const auto task = task_grain.find(g.label);
    const bool is_task = task != task_grain.end();
    const double area = g.area_px / pixels;  // of the square image
    if (!inside(g.centroid[0], g.centroid[1], 0.45) || (area < 0.01 && !is_task)) continue;
    const ImVec2 p = screen(g.centroid[0], g.centroid[1]);
    const float len = std::clamp(0.5f * std::sqrt(static_cast<float>(area)) * l.field.w, 10.0f, 0.12f * l.field.w);
    for (double t : g.cleavage_traces_deg) angle_line(draw, p, t, len * 1.2f, col(kRevealCleavage), 1.0f, nullptr);
    if (g.slow_vibration_deg) {
      angle_line(draw, p, *g.slow_vibration_deg, len, col(kRevealSlow), 2.0f, is_task ? "slow" : nullptr);
      angle_line(draw, p, *g.slow_vibration_deg + 90.0, len * 0.6f, col(kRevealFast), 2.0f, is_task ? "fast" : nullptr);
    }
    if (is_task) indicatrix_ellipse(draw, p, g, len * 0.8f);
    std::string name = is_task ? task->second + ": " + g.mineral : g.mineral;
    if (!g.relief_vs_medium.empty()) name += ", relief " + g.relief_vs_medium;
    const ImVec2 ts = ImGui::CalcTextSize(name.c_str());
    shadowed_text(draw, ImVec2(p.x - ts.x / 2, p.y - ts.y - 4), is_task ? IM_COL32(255, 220, 60, 255) : IM_COL32(255, 255, 255, 255),
                  name.c_str());
  }
}

}  // namespace pmsim::ui
