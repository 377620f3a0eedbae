// The right panel and the chart under the field: what a student reads next to the image.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "core/base/units.h"
#include "core/microscope/grain_probe.h"
#include "core/render/brightness_test.h"
#include "core/render/michel_levy_chart.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/section_becke_probe.h"
#include "core/specimen/traced_specimen.h"
#include "core/spectrum/reference_wavelengths.h"

#include "ui/app.h"
#include "ui/teaching.h"

namespace pmsim::ui {

void App::draw_chart() {
  Teaching& t = *teaching_;
  const Layout& l = layout_;
  // Rows of the chart panel: title and probe read-out, Δn labels, the chart, order labels; a
  // margin left for the thickness axis and right for the labels of lines leaving on that side.
  const float row = ImGui::GetTextLineHeight() + 2;
  const float small = ImGui::GetFontSize() * 0.85f;
  const float left = ImGui::CalcTextSize("50 um").x + 6, right = ImGui::CalcTextSize("0.000").x + 6;
  const ImVec2 p0(l.chart.x + left, l.chart.y + 2 * row);
  const ImVec2 p1(l.chart.x + l.chart.w - right, l.chart.y + l.chart.h - row);
  const Teaching::ChartKey want{scene_.illuminant, std::max(1, static_cast<int>(p1.x - p0.x)),
                                std::max(1, static_cast<int>(p1.y - p0.y))};

  // (Re)compute the chart at its drawn size off the UI thread (illuminant or window changed).
  if (!t.chart_job.valid() && (!t.chart_valid || !(t.chart_key == want))) {
    t.chart_job_key = want;
    t.chart_job = std::async(std::launch::async, [k = want] {
      return michel_levy_chart_with_lines(k.width, k.height, Teaching::kChartMaxNm, Teaching::kChartMaxUm,
                                          k.illuminant);
    });
  }
  if (t.chart_job.valid() && t.chart_job.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    t.chart_key = t.chart_job_key;
    t.chart_valid = true;  // also on failure: do not retry every frame; say why instead
    try {
      t.chart.upload(t.chart_key.width, t.chart_key.height, t.chart_job.get());
    } catch (const std::exception& e) {
      fail(std::string("Michel-Levy chart: ") + e.what());
    }
  }

  ImGui::SetNextWindowPos(ImVec2(l.chart.x, l.chart.y));
  ImGui::SetNextWindowSize(ImVec2(l.chart.w, l.chart.h));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  ImGui::Begin("##chart", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoBackground);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  ImFont* font = ImGui::GetFont();
  const ImU32 text = IM_COL32(200, 200, 200, 255);
  const auto x_of = [&](double nm) {
    return static_cast<float>(p0.x + (p1.x - p0.x) * nm / Teaching::kChartMaxNm);
  };
  const auto y_of = [&](double um) {
    return static_cast<float>(p1.y - (p1.y - p0.y) * um / Teaching::kChartMaxUm);
  };
  ImGui::SetCursorScreenPos(ImVec2(l.chart.x, l.chart.y));
  // Title left, the probe's read-out right: each shortened in turn until both fit.
  const PixelProbe& p = t.probe;
  const bool probed = p.lit && t.probe_error.empty();
  const bool x_on = p.retardation_nm <= Teaching::kChartMaxNm;
  const bool y_on = p.thickness_um > 0 && p.thickness_um <= Teaching::kChartMaxUm;
  const char* off = x_on && (y_on || p.thickness_um <= 0) ? "" : " (off the chart)";
  char titles[2][64], labels[2][128];
  std::snprintf(titles[0], sizeof titles[0], "Michel-Levy chart (%s), lines of dn",
                illuminant_name(scene_.illuminant).data());
  std::snprintf(titles[1], sizeof titles[1], "Michel-Levy (%s)", illuminant_name(scene_.illuminant).data());
  if (p.thickness_um > 0)
    std::snprintf(labels[0], sizeof labels[0], "probe: %.0f nm, order %.2f, %.1f um, dn %.4f%s",
                  p.retardation_nm, p.order, p.thickness_um, p.retardation_nm / (1000.0 * p.thickness_um),
                  off);
  else
    std::snprintf(labels[0], sizeof labels[0], "probe: %.0f nm, order %.2f%s", p.retardation_nm, p.order,
                  off);
  std::snprintf(labels[1], sizeof labels[1], "%.0f nm, order %.2f", p.retardation_nm, p.order);
  const char* title = "";
  const char* probe_label = probed ? labels[1] : "";
  for (const char* l_try : {labels[0], labels[1]}) {
    const float lw = probed ? ImGui::CalcTextSize(l_try).x + 12 : 0;
    for (const char* t_try : {titles[0], titles[1]})
      if (!*title && ImGui::CalcTextSize(t_try).x + lw <= l.chart.w) {
        title = t_try;
        if (probed) probe_label = l_try;
      }
    if (*title) break;
  }
  ImGui::TextUnformatted(title);
  if (t.chart.valid()) {
    // The texture was made for a size; while a new one is computed, stretch the old one.
    draw->AddImage(t.chart.imgui_id(), p0, p1);
  }
  // Thickness axis.
  for (double um : {0.0, 25.0, 50.0}) {
    char label[16];
    std::snprintf(label, sizeof label, um > 0 ? "%.0f um" : "0", um);
    const float w = ImGui::CalcTextSize(label).x;
    const float y = std::clamp(y_of(um) - row / 2, p0.y - 2, p1.y - row + 2);
    draw->AddText(ImVec2(p0.x - w - 4, y), text, label);
  }
  // Birefringence labels where each line leaves the chart, skipping those that would overlap.
  float next_top_x = p0.x, next_right_y = p0.y - row;
  for (const MichelLevyLine& line : t.chart_lines) {
    const float x = p0.x + (p1.x - p0.x) * static_cast<float>(line.to_frac.x);
    const float y = p0.y + (p1.y - p0.y) * static_cast<float>(line.to_frac.y);
    const ImVec2 size = font->CalcTextSizeA(small, 1e9f, 0, line.label.c_str());
    if (line.ends_on_top) {
      const float lx = x - size.x / 2;
      if (lx < next_top_x || lx + size.x > p1.x + right) continue;
      draw->AddText(font, small, ImVec2(lx, p0.y - size.y), text, line.label.c_str());
      next_top_x = lx + size.x + 4;
    } else {
      const float ly = y - size.y / 2;
      // Lines leaving on the right come down the edge as Δn grows.
      if (ly < next_right_y || ly + size.y > p1.y + row) continue;
      draw->AddText(font, small, ImVec2(p1.x + 3, ly), text, line.label.c_str());
      next_right_y = ly + size.y;
    }
  }
  // Order boundaries every kOrderWavelengthNm (the first-order red of the chart).
  for (int order = 1; order * kOrderWavelengthNm < Teaching::kChartMaxNm; ++order) {
    const float x = x_of(order * kOrderWavelengthNm);
    draw->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y + 4), IM_COL32(255, 255, 255, 90));
  }
  for (int order = 1; (order - 1) * kOrderWavelengthNm < Teaching::kChartMaxNm; ++order) {
    char label[16];
    std::snprintf(label, sizeof label, "order %d", order);
    draw->AddText(ImVec2(x_of((order - 1) * kOrderWavelengthNm) + 4, p1.y + 1), text, label);
  }
  // The plate at the probe: its retardation (vertical) and thickness (horizontal) meet on its
  // birefringence line.
  if (probed) {
    const ImU32 mark = IM_COL32(255, 255, 255, 255), shadow = IM_COL32(0, 0, 0, 255);
    const float x = x_of(std::clamp(p.retardation_nm, 0.0, Teaching::kChartMaxNm));
    if (x_on) {
      draw->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), shadow, 3.0f);
      draw->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), mark, 1.0f);
    }
    if (y_on) {
      const float y = y_of(p.thickness_um);
      draw->AddLine(ImVec2(p0.x, y), ImVec2(p1.x, y), shadow, 3.0f);
      draw->AddLine(ImVec2(p0.x, y), ImVec2(p1.x, y), mark, 1.0f);
      if (x_on) {
        draw->AddCircleFilled(ImVec2(x, y), 4, mark, 12);
        draw->AddCircle(ImVec2(x, y), 4, shadow, 12, 1.5f);
      }
    }
    const float w = ImGui::CalcTextSize(probe_label).x;
    draw->AddText(ImVec2(l.chart.x + l.chart.w - w, l.chart.y), IM_COL32(255, 255, 255, 255), probe_label);
  }
  ImGui::End();
  ImGui::PopStyleVar();
}

std::string brightness_line(double retardation_nm, Compensator accessory, Illuminant illuminant) {
  const BrightnessTest t = brightness_test(retardation_nm, accessory, illuminant);
  char b[160];
  std::snprintf(b, sizeof b, "%s at 45°: Y %.2f → %.2f adding, %.2f subtracting: %s",
                accessory == Compensator::Mica ? "Mica λ/4" : "Gypsum λ", t.y_alone, t.y_addition,
                t.y_subtraction, t.reading.c_str());
  return b;
}

void App::draw_grain_text(const GrainReport& g) {
  // What a student measures on the grain: all computed by core (report_grain) from the grain's
  // indicatrix and crystallography at the current stage angle.
  ImGui::Text("Grain %d      %s", g.id, g.mineral.c_str());
  if (g.opaque) {
    // core's report leaves the optics empty: nothing of them reaches the eyepiece.
    ImGui::TextWrapped("Opaque        black in plane light and between crossed polars at every stage angle: "
                       "no relief, colour, interference colour or extinction to read");
    ImGui::Text("Elongation    %s", g.elongation_deg ? "elongated outline" : "none (equant)");
    if (g.twin) ImGui::Text("Twinned       %s law", g.twin->law.c_str());
    return;
  }
  // A stand-in indicatrix (no optical orientation in the mineral file) must not be read as the
  // mineral's extinction (issue 22): said before the numbers it qualifies.
  if (const std::string w = grain_optics_warning(g); !w.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 190, 80, 255));
    ImGui::TextWrapped("%s", w.c_str());
    ImGui::PopStyleColor();
  }
  if (g.extinction_angle_deg)
    ImGui::Text("Extinction    %.1f deg to its %s", *g.extinction_angle_deg,
                g.cleavage_traces_deg.empty() ? "elongation" : "cleavage");
  else if (g.extinction_stage_deg.empty())
    ImGui::TextUnformatted("Extinction    at every stage angle (isotropic or cut perp. to an optic axis)");
  if (!g.extinction_stage_deg.empty())
    ImGui::Text("Extinct at    stage %.1f and %.1f deg", g.extinction_stage_deg[0], g.extinction_stage_deg[1]);
  ImGui::Text("Elongation    %s", g.sign_of_elongation ? sign_of_elongation_name(*g.sign_of_elongation)
                                                        : (g.elongation_deg ? "indeterminate" : "none (equant)"));
  if (!g.cleavage_traces_deg.empty()) {
    std::string traces;
    for (double c : g.cleavage_traces_deg) {
      char b[16];
      std::snprintf(b, sizeof b, "%s%.0f", traces.empty() ? "" : ", ", c);
      traces += b;
    }
    ImGui::Text("Cleavage      traces at %s deg", traces.c_str());
    if (g.cleavage_traces_deg.size() >= 2) {
      double a = std::fabs(g.cleavage_traces_deg[0] - g.cleavage_traces_deg[1]);
      a = std::min(a, 180.0 - a);
      ImGui::Text("              between them %.0f / %.0f deg", a, 180.0 - a);
    }
  } else {
    ImGui::TextUnformatted("Cleavage      no trace in this section");
  }
  if (g.twin)
    ImGui::Text("Twinned       %s law (twin extinct at %.1f deg)", g.twin->law.c_str(),
                g.twin->extinction_stage_deg.empty() ? 0.0 : g.twin->extinction_stage_deg[0]);
  // The compensator test by brightness (a dichromat reads Y as well as anyone): at the grain's
  // own retardation, which way the field's brightness goes with each plate.
  ImGui::TextWrapped("Compensator by brightness (grain at 45°; adding: its slow ∥ the plate's)");
  for (const Compensator c : {Compensator::Mica, Compensator::Gypsum})
    ImGui::TextWrapped("  %s", brightness_line(g.retardation_nm, c, scene_.illuminant).c_str());
  ImGui::Checkbox("Show vibration directions and cleavage", &grain_overlay_);
}

void App::draw_grain_overlay(ImDrawList* draw, float cx, float cy, float len) const {
  // Lines through the probed point at the image angles of the report (counter-clockwise from +x,
  // screen y down).
  const auto& g = teaching_->grain;
  if (!g || !grain_overlay_) return;
  auto line = [&](double deg, float half, ImU32 col, float width, const char* label) {
    const float dx = static_cast<float>(std::cos(radians(deg))) * half;
    const float dy = -static_cast<float>(std::sin(radians(deg))) * half;
    draw->AddLine(ImVec2(cx - dx, cy - dy), ImVec2(cx + dx, cy + dy), IM_COL32(0, 0, 0, 200), width + 2);
    draw->AddLine(ImVec2(cx - dx, cy - dy), ImVec2(cx + dx, cy + dy), col, width);
    if (label) draw->AddText(ImVec2(cx + dx + 3, cy + dy - 7), col, label);
  };
  for (double c : g->cleavage_traces_deg) line(c, len * 1.2f, IM_COL32(120, 200, 255, 230), 1.0f, nullptr);
  if (g->slow_vibration_deg) {
    line(*g->slow_vibration_deg, len, IM_COL32(255, 80, 60, 255), 2.0f, "slow");
    line(*g->slow_vibration_deg + 90.0, len * 0.6f, IM_COL32(255, 255, 255, 255), 2.0f, "fast");
  }
}

std::string App::becke_text() const {
  const Teaching& t = *teaching_;
  if (!t.probe_error.empty()) return {};
  if (t.becke) return describe_becke_line(*t.becke);
  if (t.section_becke) return describe_section_becke_line(*t.section_becke);
  return {};
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
  if (t.probe_job.valid() && t.probe_job.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    Teaching::ProbeResult r = t.probe_job.get();
    t.probe = std::move(r.probe);
    t.grain = std::move(r.grain);
    t.becke = std::move(r.becke);
    t.section_becke = std::move(r.section_becke);
    t.section_becke_traced = r.section_becke_traced;
    t.probe_error = std::move(r.error);
    t.spectrum.assign(t.probe.transmission.begin(), t.probe.transmission.end());
  }
  if (!t.probe_job.valid() &&
      (t.probe_generation != generation_ || t.probe_x != probe_x_ || t.probe_y != probe_y_)) {
    t.probe_generation = generation_;
    t.probe_x = probe_x_;
    t.probe_y = probe_y_;
    t.probe_job = std::async(std::launch::async, [scene = scene_, x = probe_x_, y = probe_y_, mount = t.becke_mount] {
      Teaching::ProbeResult r;
      try {
        if (scene.sample_in && scene.sample.type == SampleType::Grains) {
          const double nd = scene.sample.medium_index.value_or(kDefaultGrainMountIndex);
          const bool custom = scene.sample.crystal.has_value();
          if (!mount->specimen || custom || mount->custom || mount->mineral != scene.sample.mineral ||
              mount->medium_index != nd) {
            mount->specimen = grain_mount_specimen(scene);
            mount->mineral = scene.sample.mineral;
            mount->medium_index = nd;
            mount->custom = custom;
          }
          r.becke = probe_becke_line(*mount->specimen, scene, x, y);
          return r;
        }
        r.probe = probe_pixel(scene, x, y);
        r.grain = grain_at_image_point(scene, x, y);
        // Image points are section points only in orthoscopic view (conoscopic ones are directions).
        if (scene.sample_in && scene.sample.type == SampleType::Section && scene.mode == ViewMode::Ortho &&
            !scene.bertrand_in) {
          r.section_becke = probe_section_becke_line(scene, x, y);
          r.section_becke_traced = is_traced_specimen(scene);
        }
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
  } else if (t.becke) {
    const BeckeProbe& b = *t.becke;
    ImGui::Text("Over          %s", b.on_fragment ? scene_.sample.mineral.c_str() : "immersion liquid");
    ImGui::Text("n' (polarizer) %.4f%s", b.mineral_n, b.on_fragment ? "" : " (a fragment of this mount)");
    ImGui::Text("Liquid n_D    %.4f", b.liquid_n);
    ImGui::Text("Focus         %+.1f um", scene_.focus_um);
    ImGui::TextWrapped("Becke line: %s", becke_text().c_str());
    if (scene_.analyzer_in) ImGui::TextWrapped("%s", describe_crossed_polars(b).c_str());
  } else if (!p.lit) {
    ImGui::TextDisabled("no light reaches this point");
  } else {
    ImGui::Text("Mineral       %s", p.mineral.c_str());
    ImGui::Text("Thickness     %.1f um", p.thickness_um);
    if (p.opaque) {
      ImGui::TextUnformatted("Opaque        no light passes: no interference colour to read");
    } else {
      ImGui::Text("Retardation   %.0f nm", p.retardation_nm);
      ImGui::Text("Order         %.2f (order %d)", p.order, static_cast<int>(p.order) + 1);
    }
    if (t.grain) draw_grain_text(*t.grain);
    if (t.section_becke) {
      ImGui::Text("Focus         %+.1f um", scene_.focus_um);
      ImGui::TextWrapped("Becke line: %s", becke_text().c_str());
      if (!t.section_becke_traced)
        ImGui::TextDisabled("(seen in plane light with relief on: analyzer out, optics.relief on)");
    }
    ImGui::TextUnformatted("Transmitted spectrum, 380-780 nm");
    const float top =
        std::max(1.0f, t.spectrum.empty() ? 1.0f : *std::max_element(t.spectrum.begin(), t.spectrum.end()));
    ImGui::PlotLines("##spectrum", t.spectrum.data(), static_cast<int>(t.spectrum.size()), 0, nullptr, 0.0f,
                     top, ImVec2(l.teaching.w - 20, 90));
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
