// The right panel and the chart under the field: what a student reads next to the image.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include <imgui.h>

#include "core/render/michel_levy_chart.h"

#include "ui/app.h"
#include "ui/teaching.h"

namespace pmsim::ui {

void App::draw_chart() {
  Teaching& t = *teaching_;
  // (Re)compute the chart's colours off the UI thread when the illuminant changes.
  if (!t.chart_job.valid() && (!t.chart_valid || t.chart_illuminant != scene_.illuminant)) {
    t.chart_job_illuminant = scene_.illuminant;
    t.chart_job = std::async(std::launch::async, [il = scene_.illuminant] {
      return michel_levy_chart(Teaching::kChartColumns, 1, Teaching::kChartMaxNm, il);
    });
  }
  if (t.chart_job.valid() &&
      t.chart_job.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    try {
      t.chart.upload(Teaching::kChartColumns, 1, t.chart_job.get());
      t.chart_illuminant = t.chart_job_illuminant;
      t.chart_valid = true;
    } catch (const std::exception& e) {
      t.chart_valid = true;  // do not retry every frame; say why instead
      fail(std::string("Michel-Levy chart: ") + e.what());
    }
  }

  const Layout& l = layout_;
  ImGui::SetNextWindowPos(ImVec2(l.chart.x, l.chart.y));
  ImGui::SetNextWindowSize(ImVec2(l.chart.w, l.chart.h));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  ImGui::Begin("##chart", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBackground);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float label_h = ImGui::GetTextLineHeight() + 2;
  const ImVec2 p0(l.chart.x, l.chart.y + label_h);
  const ImVec2 p1(l.chart.x + l.chart.w, l.chart.y + l.chart.h - label_h);
  const auto x_of = [&](double nm) {
    return static_cast<float>(p0.x + (p1.x - p0.x) * nm / Teaching::kChartMaxNm);
  };
  ImGui::SetCursorScreenPos(ImVec2(l.chart.x, l.chart.y));
  ImGui::Text("Michel-Levy chart (%s), retardation 0-%.0f nm", illuminant_name(scene_.illuminant).data(),
              Teaching::kChartMaxNm);
  if (t.chart.valid()) draw->AddImage(t.chart.imgui_id(), p0, p1);
  // Order boundaries every 551 nm (the first-order red of the chart).
  for (int order = 1; order * 551.0 < Teaching::kChartMaxNm; ++order) {
    const float x = x_of(order * 551.0);
    draw->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y + 4), IM_COL32(255, 255, 255, 90));
  }
  for (int order = 1; (order - 1) * 551.0 < Teaching::kChartMaxNm; ++order) {
    char label[16];
    std::snprintf(label, sizeof label, "order %d", order);
    draw->AddText(ImVec2(x_of((order - 1) * 551.0) + 4, p1.y + 1), IM_COL32(200, 200, 200, 255),
                  label);
  }
  // The retardation at the probe, marked on the chart.
  const PixelProbe& p = t.probe;
  if (p.lit && t.probe_error.empty()) {
    const double g = std::clamp(p.retardation_nm, 0.0, Teaching::kChartMaxNm);
    const float x = x_of(g);
    draw->AddTriangleFilled(ImVec2(x - 6, p0.y - 1), ImVec2(x + 6, p0.y - 1), ImVec2(x, p0.y + 9),
                            IM_COL32(255, 255, 255, 255));
    draw->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), IM_COL32(0, 0, 0, 255), 2.0f);
    char label[64];
    std::snprintf(label, sizeof label, "at the probe: %.0f nm, order %.2f%s", p.retardation_nm,
                  p.order, p.retardation_nm > Teaching::kChartMaxNm ? " (off the chart)" : "");
    const float w = ImGui::CalcTextSize(label).x;
    draw->AddText(ImVec2(p1.x - w, l.chart.y), IM_COL32(255, 255, 255, 255), label);
  }
  ImGui::End();
  ImGui::PopStyleVar();
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
  if (t.probe_job.valid() &&
      t.probe_job.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    Teaching::ProbeResult r = t.probe_job.get();
    t.probe = std::move(r.probe);
    t.probe_error = std::move(r.error);
    t.spectrum.assign(t.probe.transmission.begin(), t.probe.transmission.end());
  }
  if (!t.probe_job.valid() &&
      (t.probe_generation != generation_ || t.probe_x != probe_x_ || t.probe_y != probe_y_)) {
    t.probe_generation = generation_;
    t.probe_x = probe_x_;
    t.probe_y = probe_y_;
    t.probe_job = std::async(std::launch::async, [scene = scene_, x = probe_x_, y = probe_y_] {
      Teaching::ProbeResult r;
      try {
        r.probe = probe_pixel(scene, x, y);
      } catch (const std::exception& e) {
        r.error = e.what();
      }
      return r;
    });
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
  if (t.figure_generation != generation_) {
    t.figure_generation = generation_;
    try {
      t.figure = describe_figure(scene_);
      t.figure_error.clear();
    } catch (const std::exception& e) {
      t.figure = FigureInfo{};
      t.figure_error = e.what();
    }
  }
  const FigureInfo& f = t.figure;
  ImGui::TextUnformatted(scene_.mode == ViewMode::Cono ? "The interference figure"
                                                       : "The crystal (conoscopic figure: C)");
  if (!t.figure_error.empty()) {
    ImGui::TextWrapped("%s", t.figure_error.c_str());
  } else {
    ImGui::Text("Kind          %s %s", f.kind.c_str(), f.optic_sign.c_str());
    if (f.kind == "biaxial") ImGui::Text("2V            %.0f deg", f.two_v_deg);
    if (!f.orientation.empty()) ImGui::TextWrapped("Cut           %s", f.orientation.c_str());
    if (!f.compensator.empty()) ImGui::TextWrapped("Compensator   %s", f.compensator.c_str());
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
