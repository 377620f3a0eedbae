// The right panel and the chart under the field: what a student reads next to the image.
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
  draw_help();
  ImGui::End();
}

void App::draw_help() {
  ImGui::SetNextItemOpen(help_open_, ImGuiCond_Always);
  const bool open = ImGui::CollapsingHeader("Keyboard shortcuts (F1)");
  if (open != help_open_) help_open_ = open;
  if (!open) return;
  if (ImGui::BeginTable("##keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    for (const Shortcut& s : shortcuts()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(key_chord_name(s.key, s.shift, s.ctrl).c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(s.what);
    }
    ImGui::EndTable();
  }
  ImGui::TextWrapped("Drag on the field to turn the stage. Hover the field to probe a point.");
}

}  // namespace pmsim::ui
