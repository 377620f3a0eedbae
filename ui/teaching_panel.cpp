// The right panel and the chart under the field: what a student reads next to the image.
#include <algorithm>

#include <imgui.h>

#include "ui/app.h"
#include "ui/teaching.h"

namespace pmsim::ui {

void App::draw_chart() {
  const Layout& l = layout_;
  ImGui::SetNextWindowPos(ImVec2(l.chart.x, l.chart.y));
  ImGui::SetNextWindowSize(ImVec2(l.chart.w, l.chart.h));
  ImGui::Begin("##chart", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings);
  ImGui::End();
}

void App::draw_teaching() {
  const Layout& l = layout_;
  ImGui::SetNextWindowPos(ImVec2(l.teaching.x, l.teaching.y));
  ImGui::SetNextWindowSize(ImVec2(l.teaching.w, l.teaching.h));
  ImGui::Begin("Observe", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  Teaching& t = *teaching_;
  // The probe follows the cursor over the field; elsewhere it stays where the cursor left it.
  if (t.probe_generation != generation_ || t.probe_x != probe_x_ || t.probe_y != probe_y_) {
    t.probe_generation = generation_;
    t.probe_x = probe_x_;
    t.probe_y = probe_y_;
    try {
      t.probe = probe_pixel(scene_, probe_x_, probe_y_);
      t.probe_error.clear();
    } catch (const std::exception& e) {
      t.probe = PixelProbe{};
      t.probe_error = e.what();
    }
    t.spectrum.assign(t.probe.transmission.begin(), t.probe.transmission.end());
  }
  const PixelProbe& p = t.probe;
  ImGui::Text("At the %s (%.2f, %.2f)", probe_hovered_ ? "cursor" : "probe", probe_x_, probe_y_);
  if (!t.probe_error.empty()) {
    ImGui::TextWrapped("%s", t.probe_error.c_str());
  } else if (!p.lit) {
    ImGui::TextDisabled("no light reaches this point");
  } else {
    ImGui::Text("Mineral       %s", p.mineral.c_str());
    ImGui::Text("Thickness     %.1f um", p.thickness_um);
    ImGui::Text("Retardation   %.0f nm", p.retardation_nm);
    ImGui::Text("Order         %.2f (order %d)", p.order, static_cast<int>(p.order) + 1);
    ImGui::TextUnformatted("Transmitted spectrum, 380-780 nm");
    const float top = std::max(1.0f, t.spectrum.empty() ? 1.0f
                                                      : *std::max_element(t.spectrum.begin(),
                                                                          t.spectrum.end()));
    ImGui::PlotLines("##spectrum", t.spectrum.data(), static_cast<int>(t.spectrum.size()), 0,
                     nullptr, 0.0f, top, ImVec2(l.teaching.w - 20, 90));
  }
  ImGui::Separator();
  draw_help();
  ImGui::End();
}

void App::draw_help() {
  ImGui::SetNextItemOpen(help_open_, ImGuiCond_Always);
  const bool open = ImGui::CollapsingHeader("Keyboard shortcuts (F1)");
  if (open != help_open_) help_open_ = open;
  if (!open) return;
  if (ImGui::BeginTable("##keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("key", ImGuiTableColumnFlags_WidthFixed, 90);
    ImGui::TableSetupColumn("action", ImGuiTableColumnFlags_WidthStretch);
    for (const Shortcut& s : shortcuts()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(key_chord_name(s.key, s.shift, s.ctrl).c_str());
      ImGui::TableNextColumn();
      ImGui::TextWrapped("%s", s.what);
    }
    ImGui::EndTable();
  }
  ImGui::TextWrapped("Drag on the field to turn the stage. Hover the field to probe a point.");
}

}  // namespace pmsim::ui
