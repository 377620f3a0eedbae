// The left panel: every microscope control, each editing one scene key of `edit`.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <memory>
#include <cstring>

#include <imgui.h>

#include "core/base/splitmix64.h"
#include "core/crystal/crystal.h"
#include "core/ebsd/read_orientation_map.h"
#include "core/microscope/map_section.h"
#include "core/microscope/scene_limits.h"
#include "core/microscope/section_map.h"
#include "core/microscope/view_geometry.h"
#include "core/render/exposure.h"
#include "core/texture/rock_recipe.h"
#include "core/specimen/grain_mount_render.h"
#include "ui/about.h"
#include "ui/app.h"
#include "ui/ui_scale.h"
#include "ui/asset_lists.h"
#include "ui/exercise_panel.h"

namespace pmsim::ui {
namespace {

bool slider_deg(const char* label, double& value_deg, double min_deg = 0, double max_deg = 360) {
  return ImGui::SliderScalar(label, ImGuiDataType_Double, &value_deg, &min_deg, &max_deg, "%.1f deg");
}

bool slider_double(const char* label, double& value, double min, double max, const char* fmt,
                   ImGuiSliderFlags flags = 0) {
  return ImGui::SliderScalar(label, ImGuiDataType_Double, &value, &min, &max, fmt, flags);
}

bool input_text(const char* label, std::string& text) {
  char buffer[1024];
  std::strncpy(buffer, text.c_str(), sizeof buffer - 1);
  buffer[sizeof buffer - 1] = '\0';
  const bool entered = ImGui::InputText(label, buffer, sizeof buffer, ImGuiInputTextFlags_EnterReturnsTrue);
  text = buffer;
  return entered;
}

template <typename E>
bool combo_enum(const char* label, E& value, std::initializer_list<const char*> names) {
  int i = static_cast<int>(value);
  std::string items;
  for (const char* n : names) items += std::string(n) + '\0';
  if (!ImGui::Combo(label, &i, items.c_str())) return false;
  value = static_cast<E>(i);
  return true;
}

// The library's minerals as a combo; true on the frame one is chosen (written into `mineral`).
bool mineral_combo(std::string& mineral) {
  static const std::vector<std::string> minerals = [] {
    try {
      return mineral_names();
    } catch (const std::exception&) {
      return std::vector<std::string>{};
    }
  }();
  bool chosen = false;
  if (ImGui::BeginCombo("Mineral", mineral.c_str())) {
    for (const auto& name : minerals)
      if (ImGui::Selectable(name.c_str(), name == mineral)) {
        mineral = name;
        chosen = true;
      }
    ImGui::EndCombo();
  }
  return chosen;
}

bool vec3_input(const char* label, std::array<double, 3>& v) {
  return ImGui::InputScalarN(label, ImGuiDataType_Double, v.data(), 3, nullptr, nullptr, "%.3f",
                             ImGuiInputTextFlags_EnterReturnsTrue);
}

constexpr struct {
  const char* name;
  double magnification, na;
} kObjectiveChoices[] = {
    {"4x / 0.10", 4, 0.10}, {"10x / 0.25", 10, 0.25}, {"40x / 0.65", 40, 0.65}, {"50x / 0.85", 50, 0.85}};

bool is_biaxial(const Scene& s) {
  if (s.sample.crystal) return !s.sample.crystal->uniaxial;
  try {
    return find_mineral(s.sample.mineral).symmetry() == CrystalSymmetry::Biaxial;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

void App::draw_controls(Scene& edit, bool& changed) {
  const Layout& l = layout_;
  ImGui::SetNextWindowPos(ImVec2(l.controls.x, l.controls.y));
  ImGui::SetNextWindowSize(ImVec2(l.controls.w, l.controls.h));
  ImGui::Begin("Microscope", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  ImGui::PushItemWidth(l.controls.w * 0.55f);
  if (ImGui::BeginTabBar("##tabs")) {
    if (ImGui::BeginTabItem("Microscope")) {
      draw_microscope_tab(edit, changed);
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Sample")) {
      draw_sample_tab(edit, changed);
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Quality")) {
      draw_quality_tab(edit, changed);
      ImGui::EndTabItem();
    }
    if (exercise_) {
      // Shown while an exercise is open; E (or opening one) brings it to the front.
      const bool select = exercise_->select_tab;
      exercise_->select_tab = false;
      if (ImGui::BeginTabItem("Exercise", nullptr, select ? ImGuiTabItemFlags_SetSelected : 0)) {
        draw_exercise_tab(edit, changed);
        ImGui::EndTabItem();
      }
    }
    if (ImGui::BeginTabItem("Files")) {
      draw_files_tab();
      ImGui::EndTabItem();
    }
    {
      // The determinative aid (ui/identify_panel.cpp); a script's `identify` brings it to the front.
      const bool select = identify_.select_tab;
      identify_.select_tab = false;
      if (ImGui::BeginTabItem("Identify", nullptr, select ? ImGuiTabItemFlags_SetSelected : 0)) {
        draw_identify_tab();
        ImGui::EndTabItem();
      }
    }
    if (ImGui::BeginTabItem("About")) {
      draw_about_tab();
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

void App::draw_microscope_tab(Scene& edit, bool& changed) {
  // One click for the whole conoscopic set-up: condenser top lens and Bertrand lens together.
  const bool cono = edit.mode == ViewMode::Cono;
  ImGui::TextUnformatted("View");
  if (ImGui::RadioButton("Orthoscopic", !cono) && cono) {
    edit.mode = ViewMode::Ortho;
    edit.bertrand_in = false;
    changed = true;
  }
  ImGui::SameLine();
  if (ImGui::RadioButton("Conoscopic", cono) && !cono) {
    edit.mode = ViewMode::Cono;
    edit.bertrand_in = true;
    changed = true;
  }
  changed |= ImGui::Checkbox("Bertrand lens in", &edit.bertrand_in);

  ImGui::Separator();
  ImGui::TextUnformatted("Stage and polars");
  changed |= slider_deg("Stage", edit.stage_deg);
  // The mechanical stage: the section point under the crosshair (right-drag or Shift-drag on the
  // field, Ctrl + arrows).
  const ImGuiInputTextFlags enter_xy = ImGuiInputTextFlags_EnterReturnsTrue;
  changed |= ImGui::InputDouble("Stage X", &edit.stage.x_mm, 0.1, 1.0, "%.3f mm", enter_xy);
  changed |= ImGui::InputDouble("Stage Y", &edit.stage.y_mm, 0.1, 1.0, "%.3f mm", enter_xy);
  changed |= slider_deg("Polarizer", edit.polarizer_deg);
  changed |= ImGui::Checkbox("Analyzer in", &edit.analyzer_in);
  ImGui::SameLine();
  if (ImGui::SmallButton("Cross polars")) {
    edit.analyzer_in = true;
    edit.analyzer_deg = wrap_deg(edit.polarizer_deg + 90);
    changed = true;
  }
  changed |= slider_deg("Analyzer", edit.analyzer_deg);

  ImGui::Separator();
  ImGui::TextUnformatted("Accessory slot (slow direction NE-SW)");
  changed |= combo_enum("Compensator", edit.compensator,
                        {"none", "gypsum (550 nm)", "mica (147 nm)", "quartz wedge"});
  if (edit.compensator == Compensator::QuartzWedge)
    changed |= slider_double("Wedge pushed in", edit.compensator_position, 0.0, 1.0, "%.2f");

  ImGui::Separator();
  int objective = -1;
  for (int i = 0; i < 4; ++i)
    if (std::abs(edit.objective.magnification - kObjectiveChoices[i].magnification) < 1e-9 &&
        std::abs(edit.objective.na - kObjectiveChoices[i].na) < 1e-9)
      objective = i;
  if (ImGui::BeginCombo("Objective", objective >= 0 ? kObjectiveChoices[objective].name : "custom")) {
    for (int i = 0; i < 4; ++i)
      if (ImGui::Selectable(kObjectiveChoices[i].name, i == objective)) {
        edit.objective.magnification = kObjectiveChoices[i].magnification;
        edit.objective.na = kObjectiveChoices[i].na;
        changed = true;
      }
    ImGui::EndCombo();
  }
  changed |= ImGui::InputDouble("Field number", &edit.eyepiece.field_number_mm, 1.0, 2.0, "%.1f mm",
                                ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::TextDisabled("field of view %.3f mm (field number / magnification)", field_of_view_mm(edit));
  changed |= slider_double("Condenser NA", edit.condenser.na, 0.05, 1.3, "%.2f");
  // The aperture diaphragm (condenser.aperture_na, 0 = stopped down) can open up to the
  // condenser's own NA; lowering the condenser NA below it closes it with it.
  edit.condenser.aperture_na = std::min(edit.condenser.aperture_na, edit.condenser.na);
  changed |= slider_double("Aperture diaphragm", edit.condenser.aperture_na, 0.0, edit.condenser.na, "NA %.2f");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("condenser.aperture_na: 0 = stopped down (nearly parallel light)");
  // Fine focus (focus_um, + = objective up): also Shift+Up/Down (1 um) and Ctrl + mouse wheel over the field.
  changed |= slider_double("Fine focus", edit.focus_um, -50.0, 50.0, "%+.1f um");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("focus_um: 0 = specimen mid-plane, + = focusing up");
  changed |= combo_enum("Illuminant", edit.illuminant, {"D65 (daylight)", "A (tungsten)"});
  ImGui::Separator();
  ImGui::Checkbox("Eyepiece crosshair", &reticle_);
  ImGui::SameLine();
  ImGui::Checkbox("Scale bar", &scale_bar_);
}

void App::draw_sample_tab(Scene& edit, bool& changed) {
  SampleSettings& s = edit.sample;
  bool present = edit.sample_in;
  if (ImGui::Checkbox("Sample on the stage", &present)) {
    edit.sample_in = present;
    changed = true;
  }
  changed |= combo_enum("Type", s.type, {"plate", "wedge", "thin section", "grains"});

  if (s.type == SampleType::Grains) {
    // A grain mount: fragments of sample.mineral in an immersion liquid of n_D sample.medium_index,
    // traced with its polarization by core/specimen: plane light with the analyzer out,
    // interference colours with it in.
    if (mineral_combo(s.mineral)) {
      s.crystal.reset();
      changed = true;
    }
    double nd = s.medium_index.value_or(kDefaultGrainMountIndex);
    if (slider_double("Liquid n_D", nd, kMinMediumIndex, kMaxMediumIndex, "%.3f")) {
      s.medium_index = nd;
      changed = true;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("sample.medium_index: n_D of the immersion liquid");
    ImGui::TextDisabled(edit.analyzer_in ? "analyzer in: interference colours; focus and aperture in the Microscope tab"
                                         : "plane light; focus and aperture in the Microscope tab");
    return;
  }

  if (s.type == SampleType::Section) {
    // Section files, then the EBSD maps shipped in assets/ebsd (by file name, extension kept:
    // sample.section tells a map by it); any other map by its path.
    static const std::vector<std::string> sections = [] {
      std::vector<std::string> v = list_asset_stems("sections", ".json");
      for (const std::string& r : list_asset_stems("rocks", ".json"))
        if (std::find(v.begin(), v.end(), r) == v.end()) v.push_back(r);  // grown rocks (core/texture)
      for (const char* ext : {".ctf", ".ang"})
        for (const std::string& m : list_asset_stems("ebsd", ext)) v.push_back(m + ext);
      return v;
    }();
    if (ImGui::BeginCombo("Section", s.section.c_str())) {
      for (const auto& name : sections)
        if (ImGui::Selectable(name.c_str(), name == s.section)) {
          s.section = name;
          changed = true;
        }
      ImGui::EndCombo();
    }
    changed |= input_text("Section or map file", s.section);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("a thin-section .json, or an EBSD orientation map .ctf (Oxford) / .ang (EDAX); Enter opens it");
    if (ImGui::Button("Browse...##section")) browse(Browse::Section);
    draw_rock_seed(s, changed);
    if (is_orientation_map_path(s.section))
      changed |= combo_enum("Non-indexed points", s.nonindexed, {"mounting medium", "black"});
    changed |= slider_double("Thickness", s.thickness_um, 1.0, 100.0, "%.1f um");
    draw_slide_overview(edit, changed);
    return;
  }

  bool custom = s.crystal.has_value();
  if (!custom) {
    changed |= mineral_combo(s.mineral);
  }
  if (ImGui::Checkbox("Custom crystal by indices", &custom)) {
    if (custom)
      s.crystal = CrystalIndices{};
    else
      s.crystal.reset();
    changed = true;
  }
  if (s.crystal) {
    CrystalIndices& c = *s.crystal;
    int kind = c.uniaxial ? 0 : 1;
    if (ImGui::RadioButton("uniaxial", &kind, 0) | ImGui::RadioButton("biaxial", &kind, 1)) {
      c.uniaxial = kind == 0;
      changed = true;
    }
    const ImGuiInputTextFlags enter = ImGuiInputTextFlags_EnterReturnsTrue;
    if (c.uniaxial) {
      changed |= ImGui::InputDouble("n omega (no)", &c.no, 0.001, 0.01, "%.4f", enter);
      changed |= ImGui::InputDouble("n epsilon (ne)", &c.ne, 0.001, 0.01, "%.4f", enter);
    } else {
      changed |= ImGui::InputDouble("n alpha", &c.nalpha, 0.001, 0.01, "%.4f", enter);
      changed |= ImGui::InputDouble("n beta", &c.nbeta, 0.001, 0.01, "%.4f", enter);
      changed |= ImGui::InputDouble("n gamma", &c.ngamma, 0.001, 0.01, "%.4f", enter);
    }
  }

  const double max_um = s.type == SampleType::Wedge ? 500.0 : 200.0;
  changed |= slider_double("Thickness", s.thickness_um, 0.5, max_um, "%.1f um", ImGuiSliderFlags_Logarithmic);
  ImGui::TextDisabled(s.type == SampleType::Wedge ? "(wedge: thickness at the right edge)" : " ");

  ImGui::Separator();
  ImGui::TextUnformatted("Cut (crystal axes at stage 0 deg, lab x east, z up)");
  if (!is_biaxial(edit)) {
    if (ImGui::SmallButton("perp. c (basal)")) s.optic_axis = {0, 0, 1}, changed = true;
    ImGui::SameLine();
    if (ImGui::SmallButton("parallel c")) s.optic_axis = {1, 0, 0}, changed = true;
    ImGui::SameLine();
    if (ImGui::SmallButton("c at 30 deg")) s.optic_axis = {0.5, 0, 0.8660254}, changed = true;
    changed |= vec3_input("Optic axis", s.optic_axis);
  } else {
    if (ImGui::SmallButton("Bxa figure")) s.x_axis = {1, 0, 0}, s.z_axis = {0, 0, 1}, changed = true;
    ImGui::SameLine();
    if (ImGui::SmallButton("optic normal")) s.x_axis = {1, 0, 0}, s.z_axis = {0, 1, 0}, changed = true;
    changed |= vec3_input("X (n alpha)", s.x_axis);
    changed |= vec3_input("Z (n gamma)", s.z_axis);
  }
}

// A rock with a recipe grows again from another seed (sample.seed, core/texture): "New specimen"
// is the teacher's fresh slide of the same rock. A section file cannot be regrown, so a seed left
// from a rock is dropped when another section is chosen.
void App::draw_rock_seed(SampleSettings& s, bool& changed) {
  if (rock_recipe_path(s.section).empty()) {
    if (s.seed) {
      s.seed.reset();
      changed = true;
    }
    return;
  }
  if (ImGui::Button("New specimen")) {
    // The next seed along a fixed sequence: reproducible, and 0 … 2³¹ − 1 as sample.seed takes.
    s.seed = static_cast<int>(splitmix64(static_cast<std::uint64_t>(s.seed.value_or(0)) + 1) & 0x7FFFFFFFu);
    changed = true;
  }
  ImGui::SameLine();
  ImGui::TextDisabled("%s", s.seed ? ("seed " + std::to_string(*s.seed)).c_str() : "the recipe's seed");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("sample.seed: the same rock grown again; every grain differs, the modes and textures stay");
}

void App::draw_slide_overview(Scene& edit, bool& changed) {
  // The slide seen from above at stage 0°: the section's extent, and the field of view as a circle
  // around the point under the crosshair. A click moves the stage there.
  const SampleSettings& s = edit.sample;
  std::string key = s.section + "|" + (s.seed ? std::to_string(*s.seed) : "-") + "|" +
                    (s.orientation_seed ? std::to_string(*s.orientation_seed) : "-") + "|" +
                    std::to_string(static_cast<int>(s.nonindexed));
  for (const auto& [phase, mineral] : s.phases) key += "|" + phase + "=" + mineral;
  if (key != slide_.key) {  // another section: loaded (grown) on a thread of its own
    slide_ = SlideSection{};
    slide_.key = key;
    slide_.job = std::async(std::launch::async, [scene = edit] { return load_scene_section(scene); });
  }
  if (slide_.job.valid() && slide_.job.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    try {
      slide_.map = slide_.job.get();
    } catch (const std::exception&) {
      slide_.failed = true;  // reported by the scene check on commit
    }
  }
  if (slide_.failed) return;
  if (!slide_.map) {
    ImGui::TextDisabled("Slide: preparing the section...");
    return;
  }
  const std::shared_ptr<const SectionMap>& map = slide_.map;
  ImGui::TextUnformatted("Slide (click to move the stage)");
  const float avail = ImGui::GetContentRegionAvail().x;
  const double margin_mm = 0.1 * std::max(map->width_mm, map->height_mm);
  const double span_w = map->width_mm + 2 * margin_mm, span_h = map->height_mm + 2 * margin_mm;
  const float scale = static_cast<float>(std::min(avail / span_w, 160.0 / span_h));
  const ImVec2 size(static_cast<float>(span_w * scale), static_cast<float>(span_h * scale));
  const ImVec2 o = ImGui::GetCursorScreenPos();
  const ImVec2 centre(o.x + size.x / 2, o.y + size.y / 2);
  auto to_screen = [&](double x_mm, double y_mm) {
    return ImVec2(centre.x + static_cast<float>(x_mm * scale), centre.y - static_cast<float>(y_mm * scale));
  };
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(o, ImVec2(o.x + size.x, o.y + size.y), IM_COL32(60, 62, 66, 255));  // the slide
  draw->AddRectFilled(to_screen(-map->width_mm / 2, map->height_mm / 2), to_screen(map->width_mm / 2, -map->height_mm / 2),
                      IM_COL32(150, 140, 120, 255));  // the section under its cover glass
  const ImVec2 f = to_screen(edit.stage.x_mm, edit.stage.y_mm);
  draw->AddCircle(f, std::max(2.0f, static_cast<float>(field_of_view_mm(edit) / 2 * scale)), IM_COL32(255, 220, 60, 255),
                  32, 1.5f);
  ImGui::InvisibleButton("slide_overview", size);
  if (ImGui::IsItemActive()) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    edit.stage.x_mm = (m.x - centre.x) / scale;
    edit.stage.y_mm = -(m.y - centre.y) / scale;
    changed = true;
  }
  ImGui::Text("section %.1f x %.1f mm", map->width_mm, map->height_mm);
}

void App::draw_quality_tab(Scene& edit, bool& changed) {
  RenderSettings& r = edit.render;
  OpticsSettings& o = edit.optics;
  changed |= combo_enum("Lens model", o.lens_model, {"auto", "ideal", "physical (SML)"});
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("auto: per element the cheapest model whose error stays within tolerance");
  changed |= ImGui::SliderInt("Lens depth dT", &o.lens_depth, 0, 4);
  bool schlick = o.fresnel == FresnelModel::Schlick;
  if (ImGui::Checkbox("Schlick Fresnel", &schlick)) {
    o.fresnel = schlick ? FresnelModel::Schlick : FresnelModel::Exact;
    changed = true;
  }
  changed |= ImGui::Checkbox("Relief (refracting section)", &o.relief);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("optics.relief: a thin section (orthoscopic; analyzer out, or in without a\n"
                      "compensator) is traced as a 3-D slab: relief, grain outlines, cleavage cracks,\n"
                      "the Becke line with the fine focus; between crossed polars the colours with\n"
                      "those outlines");
  ImGui::Separator();
  changed |= ImGui::SliderInt("Wavelengths", &r.wavelengths, 0, 128, r.wavelengths ? "%d" : "auto");
  changed |= ImGui::SliderInt("Samples/pixel", &r.spp, 0, 64, r.spp ? "%d" : "auto");
  changed |= slider_double("Tolerance", r.tolerance_de2000, 0.1, 5.0, "%.2f dE00");
  changed |= slider_double("Exposure", r.exposure_ev, kMinExposureEv, kMaxExposureEv, "%+.1f EV");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("stops: the field and PNG exports x 2^EV (e.g. -1 keeps a Becke line's excess light from clipping)");
  changed |= combo_enum("Seen as", r.vision, {"normal vision", "protanopia", "deuteranopia", "tritanopia"});
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("render.vision: the field and PNG exports as an observer with that colour-vision\n"
                      "deficiency sees them (Machado, Oliveira & Fernandes 2009), for teachers");
  // ui.scale: the interface's size, not the scene's (no restart).
  bool automatic = !ui_scale_setting().has_value();
  if (ImGui::Checkbox("Auto UI scale", &automatic)) set_ui_scale(automatic ? std::nullopt : std::optional<double>(ui_scale()));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("ui.scale=auto: follow the monitor's content scale");
  if (!automatic) {
    // Applied on release: rescaling under the dragged slider would move it away from the mouse.
    if (!ImGui::IsAnyItemActive() || ui_scale_edit_ <= 0.0f) ui_scale_edit_ = ui_scale();
    ImGui::SliderFloat("UI scale", &ui_scale_edit_, float(kUiScaleMin), float(kUiScaleMax), "%.2f");
    if (ImGui::IsItemDeactivatedAfterEdit()) set_ui_scale(ui_scale_edit_);
  }
  static const int kSizes[] = {128, 256, 384, 512, 768};
  if (ImGui::BeginCombo("Image size", (std::to_string(r.width) + " x " + std::to_string(r.height)).c_str())) {
    for (int s : kSizes)
      if (ImGui::Selectable((std::to_string(s) + " x " + std::to_string(s)).c_str(), s == r.width)) {
        r.width = r.height = s;
        changed = true;
      }
    ImGui::EndCombo();
  }
  bool mono = r.single_wavelength_nm > 0;
  if (ImGui::Checkbox("Monochromatic", &mono)) {
    r.single_wavelength_nm = mono ? 589.0 : 0.0;
    changed = true;
  }
  if (mono) changed |= slider_double("Wavelength", r.single_wavelength_nm, 380, 780, "%.0f nm");

  ImGui::Separator();
  const RenderImage& im = image_;
  ImGui::Text("Render time   %.0f ms", im.time_ms);
  ImGui::Text("Samples/pixel %.1f (%d wavelengths, %d passes)", im.samples_per_pixel, im.wavelengths,
              im.passes);
  if (im.error_estimate)
    ImGui::Text("Error         %.2f dE00 %s", *im.error_estimate, im.converged ? "(converged)" : "");
  else
    ImGui::TextUnformatted("Error         not estimated yet");
  ImGui::Text("UI            %.1f fps, frame build %.1f ms", counters_.fps, counters_.frame_ms);
  if (!im.model_report.empty()) {
    ImGui::TextUnformatted("Models chosen:");
    ImGui::PushTextWrapPos(0);
    ImGui::TextUnformatted(im.model_report.c_str());
    ImGui::PopTextWrapPos();
  }
}

void App::draw_files_tab() {
  ImGui::PushItemWidth(-1);
  ImGui::TextUnformatted("Scene file");
  bool load = input_text("##scene", scene_path_);
  load |= ImGui::Button("Load");
  ImGui::SameLine();
  if (ImGui::Button("Save")) save_scene(scene_path_);
  ImGui::SameLine();
  if (ImGui::Button("Browse...##scene")) browse(Browse::Scene);
  ImGui::SameLine();
  if (ImGui::Button("Open exercise...")) browse(Browse::Exercise);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a student's <name>.pmexercise.json (pmsim-exercise make)");
  if (load) load_scene(scene_path_);
  static const std::vector<std::string> scenes = list_asset_stems("scenes", ".json");
  ImGui::TextUnformatted("Example scenes (assets/scenes)");
  ImGui::BeginChild("##scenes", ImVec2(0, 150), true);
  for (const auto& name : scenes)
    if (ImGui::Selectable(name.c_str())) load_scene(asset_dir() + "/scenes/" + name + ".json");
  ImGui::EndChild();

  ImGui::Separator();
  ImGui::TextUnformatted("Export the field (.png sRGB, .exr linear)");
  input_text("##field", field_path_);
  if (ImGui::Button("Export field")) export_field(field_path_);
  ImGui::TextUnformatted("Screenshot of the window (.png)");
  input_text("##window", window_path_);
  if (ImGui::Button("Save window")) request_window_screenshot(window_path_);
  if (!notice_.empty()) ImGui::TextWrapped("%s", notice_.c_str());
  ImGui::PopItemWidth();
}

void App::draw_about_tab() {
  for (const std::string& line : about_lines()) ImGui::TextWrapped("%s", line.c_str());
}

}  // namespace pmsim::ui
