#include "ui/app.h"

#include "core/specimen/instrument_response.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "core/io/image_file.h"
#include "core/render/exposure.h"
#include "core/base/input_error.h"
#include "core/base/units.h"  // kPi, radians, degrees
#include "core/io/scene_file.h"
#include "core/microscope/native_resolution.h"
#include "core/microscope/sample_source.h"
#include "core/microscope/scene_check.h"
#include "core/microscope/scene_limits.h"
#include "core/microscope/view_geometry.h"
#include "core/render/progressive_renderer.h"
#include "core/render/scale_bar.h"
#include "ui/asset_lists.h"
#include "ui/exercise_panel.h"
#include "ui/teaching.h"
#include "ui/ui_scale.h"

namespace pmsim::ui {
namespace {

// The objective turret, in the order of the 1…4 shortcuts.
constexpr struct {
  double magnification, na;
} kObjectives[] = {{4, 0.10}, {10, 0.25}, {40, 0.65}, {50, 0.85}};
// One step of the fine focus (a key press or a wheel notch): 1 µm, the graduation of a
// petrographic microscope's fine-focus knob, a small fraction of a 30–300 µm fragment.
constexpr double kFocusStepUm = 1.0;

// Exports and screenshots go where the user says, creating the folder (e.g. out/ui/) if needed.
void make_parent_folder(const std::string& path) {
  const auto parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
}

// A scene path as typed: as is when it exists, else relative to the assets folder (so scripts
// and the path field can say "assets/scenes/calcite_cono.json" from anywhere).
std::string resolve_scene_path(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty() || fs::exists(path, ec) || fs::path(path).is_absolute()) return path;
  const std::string under_assets = path.rfind("assets/", 0) == 0 ? path.substr(7) : path;
  const fs::path candidate = fs::path(asset_dir()) / under_assets;
  return fs::exists(candidate, ec) ? candidate.string() : path;
}

std::string extension_lower(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

double wrap_deg(double angle_deg) {
  if (!std::isfinite(angle_deg)) return 0.0;
  double a = std::fmod(angle_deg, 360.0);
  if (a < 0) a += 360.0;
  return a >= 360.0 ? 0.0 : a;
}

App::App(const Scene& scene, int renderer_threads)
    : scene_(scene),
      feed_(std::make_unique<RenderFeed>(renderer_threads)),
      teaching_(std::make_unique<Teaching>()) {
  // The style the driver set up, kept unscaled so that every ui.scale starts from it.
  if (ImGui::GetCurrentContext()) base_style_ = std::make_unique<ImGuiStyle>(ImGui::GetStyle());
  layout_ = compute_layout(window_w_, window_h_);
  try {
    validate_scene(scene_);
    check_scene(scene_);
  } catch (const std::exception& e) {
    // A bad initial scene (the drivers validate before, so only from code): show it and render
    // the defaults rather than nothing.
    fail(e.what());
    scene_ = Scene{};
  }
  previous_scene_ = scene_;
  generation_ = 1;
  feed_->submit(scene_, generation_);
}

// A student who closes the window keeps the answers typed since the last save.
App::~App() {
  if (exercise_ && exercise_->unsaved) exercise_save();
  feed_.reset();
}

void App::set_window_size(int width, int height) {
  window_w_ = width;
  window_h_ = height;
  layout_ = compute_layout(width, height, ui_scale());
}

void App::set_content_scale(float scale) {
  content_scale_ = std::clamp(scale, float(kUiScaleMin), float(kUiScaleMax));
  apply_scale();
}

void App::set_ui_scale(std::optional<double> scale) {
  ui_scale_ = scale ? std::optional<float>(float(*scale)) : std::nullopt;
  apply_scale();
}

void App::apply_scale() {
  if (base_style_ && ImGui::GetCurrentContext()) apply_ui_scale(*base_style_, ui_scale());
  layout_ = compute_layout(window_w_, window_h_, ui_scale());
}

bool App::commit(const Scene& candidate) {
  // Checked here, synchronously, so a bad value is refused in the frame it was made; the
  // renderer restarts on the feed's thread.
  try {
    validate_scene(candidate);
    check_scene(candidate);
  } catch (const std::exception& e) {
    fail(e.what());
    ++counters_.rejected;
    return false;
  }
  // The exposure and the colour vision change how the image is shown, not the image: no restart,
  // a re-upload.
  if (candidate.render.exposure_ev != scene_.render.exposure_ev || candidate.render.vision != scene_.render.vision) {
    Scene same = candidate;
    same.render.exposure_ev = scene_.render.exposure_ev;
    same.render.vision = scene_.render.vision;
    if (scene_to_json(same) == scene_to_json(scene_)) {
      previous_scene_ = scene_;
      scene_ = candidate;
      if (image_.width > 0)
        field_texture_.upload(image_.width, image_.height, image_.rgb,
                              display_matrix(scene_.render.exposure_ev, scene_.render.vision));
      ++counters_.commits;
      error_.clear();
      return true;
    }
  }
  previous_scene_ = scene_;
  scene_ = candidate;
  ++generation_;
  feed_->submit(scene_, generation_);
  change_frame_ = counters_.frames;
  ++counters_.commits;
  error_.clear();
  return true;
}

bool App::set(std::string_view assignment) {
  if (is_ui_setting(assignment)) {
    const auto eq = assignment.find('=');
    const std::string_view key = assignment.substr(0, eq), value = eq == std::string_view::npos ? "" : assignment.substr(eq + 1);
    try {
      if (key != "ui.scale") throw InputError("", std::string(key), std::string(value), "unknown key (the UI's keys: ui.scale)");
      set_ui_scale(parse_ui_scale(value));
      return true;
    } catch (const std::exception& e) {
      fail(e.what());
      ++counters_.rejected;
      return false;
    }
  }
  Scene candidate = scene_;
  try {
    apply_setting(candidate, assignment);
  } catch (const std::exception& e) {
    fail(e.what());
    ++counters_.rejected;
    return false;
  }
  return commit(candidate);
}

void App::fail(const std::string& message) {
  // InputError says "command line" for values that came without a file: here, the UI.
  const std::string prefix = "command line: ";
  error_ = message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
  ++counters_.failures;
  if (expected_error_.empty()) {
    std::fprintf(stderr, "pmsim: %s\n", message.c_str());
  } else if (!expected_error_said_) {
    std::fprintf(stderr, "pmsim: expected error (%s): %s\n", expected_error_.c_str(), error_.c_str());
    expected_error_said_ = true;
  }
}

void App::note(const std::string& message) { notice_ = message; }

bool App::load_scene(const std::string& typed_path) {
  const std::string path = resolve_scene_path(typed_path);
  // A student's exercise file is a scene and more: its tasks open in the Exercise tab.
  if (path.ends_with(".pmexercise.json")) return open_exercise(path);
  std::vector<std::string> warnings;
  Scene loaded;
  try {
    loaded = load_scene_file(path, &warnings);
  } catch (const std::exception& e) {
    fail(e.what());
    ++counters_.rejected;
    return false;
  }
  for (const auto& w : warnings) std::fprintf(stderr, "pmsim: warning: %s\n", w.c_str());
  if (!commit(loaded)) return false;
  scene_path_ = path;
  note("loaded " + path);
  return true;
}

bool App::save_scene(const std::string& path) {
  try {
    make_parent_folder(path);
    save_scene_file(scene_, path);
  } catch (const std::exception& e) {
    fail(e.what());
    return false;
  }
  note("saved " + path);
  return true;
}

bool App::export_field(const std::string& path) {
  if (image_.width <= 0) {
    fail("export " + path + ": no image rendered yet");
    return false;
  }
  const std::string ext = extension_lower(path);
  if (ext != ".png" && ext != ".exr" && ext != ".tif" && ext != ".tiff") {
    fail("export " + path + ": use .png (sRGB) or .exr / .tif (linear)");
    return false;
  }
  try {
    // render.native=on on an EBSD map: the export has one pixel per map point, as pmsim-render
    // writes it (native_resolution.h), rendered to convergence for it; the view keeps its own size.
    const Scene native = native_resolution_scene(scene_);
    const bool reframed = native.render.width != scene_.render.width || native.render.height != scene_.render.height ||
                          native.eyepiece.field_number_mm != scene_.eyepiece.field_number_mm;
    RenderImage native_image;
    if (reframed) {
      validate_scene(native);  // the map's size against the render limits, as any render.width
      native_image = render_microscope_scene(native);  // the source the screen's view uses
    }
    const RenderImage& img = reframed ? native_image : image_;
    const Scene& shown = reframed ? native : scene_;
    make_parent_folder(path);
    // The exposure and colour vision as on screen, for an 8-bit export (PNG); EXR and TIFF stay linear.
    const bool eight_bit = std::filesystem::path(path).extension() == ".png";
    std::vector<float> rgb =
        eight_bit ? displayed(img.rgb, shown.render.exposure_ev, shown.render.vision) : img.rgb;
    if (scale_bar_ && shown.mode == ViewMode::Ortho && !shown.bertrand_in)
      burn_scale_bar(rgb, img.width, img.height, choose_scale_bar(mm_per_pixel(shown, img.width, img.height), img.width));
    write_image(path, img.width, img.height, rgb, scene_to_json(shown));
  } catch (const std::exception& e) {
    fail(e.what());
    return false;
  }
  note("field exported to " + path);
  return true;
}

std::optional<std::string> App::take_window_screenshot_request() {
  auto r = window_shot_;
  window_shot_.reset();
  return r;
}

bool App::write_window_pixels(const std::string& path, int width, int height,
                              const std::vector<std::uint8_t>& rgb8) {
  try {
    make_parent_folder(path);
    write_image_rgb8(path, width, height, rgb8, scene_to_json(scene_));
  } catch (const std::exception& e) {
    fail(e.what());
    return false;
  }
  note("window saved to " + path);
  return true;
}

bool App::wait_rendered(double timeout_s) const { return feed_->wait(timeout_s); }

void App::pull_snapshot() {
  if (auto failure = feed_->take_failure(); failure && failure->id == generation_) {
    // Refused by the renderer after our own checks passed: back to the scene before.
    fail(failure->message);
    ++counters_.rejected;
    scene_ = previous_scene_;
    feed_->submit(scene_, ++generation_);
  }
  if (feed_->snapshot(image_, image_current_)) {
    field_texture_.upload(image_.width, image_.height, image_.rgb,
                          display_matrix(scene_.render.exposure_ev, scene_.render.vision));
    ++counters_.uploads;
  }
}

void App::frame() {
  const auto t0 = std::chrono::steady_clock::now();
  pull_snapshot();

  poll_exercise();
  Scene edit = scene_;
  bool changed = false;
  draw_controls(edit, changed);
  draw_field(edit, changed);
  draw_status();
  draw_chart();
  draw_teaching();
  draw_file_browser();
  handle_shortcuts(edit, changed);
  if (changed) {
    edit.stage_deg = wrap_deg(edit.stage_deg);
    commit(edit);
  }
  // Again after the changes: the texture is drawn when ImGui renders, after this, so a first
  // image that arrived while the frame was built is on screen in this frame, not the next.
  pull_snapshot();

  ++counters_.frames;
  if (change_frame_ && image_current_) {
    const std::uint64_t frames = counters_.frames - *change_frame_;
    ++counters_.first_images;
    counters_.first_image_frames += frames;
    counters_.first_image_frames_max = std::max(counters_.first_image_frames_max, frames);
    change_frame_.reset();
  }
  counters_.frame_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void App::draw_field(Scene& edit, bool& changed) {
  const Layout& l = layout_;
  ImGui::SetNextWindowPos(ImVec2(l.view.x, l.view.y));
  ImGui::SetNextWindowSize(ImVec2(l.view.w, l.view.h));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  ImGui::Begin("##field", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoScrollWithMouse | ImGuiWindowFlags_NoBackground);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 p0(l.field.x, l.field.y), p1(l.field.x + l.field.w, l.field.y + l.field.h);
  const float r = l.field_radius();
  const ImVec2 c(l.field.cx(), l.field.cy());
  // The field stop of the eyepiece: the image seen through a circle, as in the instrument.
  if (field_texture_.valid())
    draw->AddImageRounded(field_texture_.imgui_id(), p0, p1, ImVec2(0, 0), ImVec2(1, 1), IM_COL32_WHITE, r);
  else
    draw->AddCircleFilled(c, r, IM_COL32(0, 0, 0, 255), 96);
  draw->AddCircle(c, r, IM_COL32(10, 10, 10, 255), 96, 2.0f);
  if (reticle_) {
    const ImU32 line = IM_COL32(15, 15, 15, 150);
    draw->AddLine(ImVec2(c.x - r, c.y), ImVec2(c.x + r, c.y), line);
    draw->AddLine(ImVec2(c.x, c.y - r), ImVec2(c.x, c.y + r), line);
  }

  if (scale_bar_ && scene_.mode == ViewMode::Ortho && !scene_.bertrand_in) draw_scale_bar(draw);
  if (exercise_) {
    draw_task_markers(draw);
    draw_reveal(draw);
  }

  // Grabbing the stage: dragging around the centre turns it by the angle swept; dragging with the
  // right button (or Shift + left) translates it, the section point under the cursor staying
  // under the cursor as on a mechanical stage.
  ImGui::SetCursorScreenPos(p0);
  ImGui::InvisibleButton("field_stage", ImVec2(l.field.w, l.field.h),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  const ImVec2 m = ImGui::GetIO().MousePos;
  const double mouse_angle_deg = degrees(std::atan2(-(m.y - c.y), m.x - c.x));
  const bool translate = ImGui::IsMouseDown(ImGuiMouseButton_Right) || ImGui::GetIO().KeyShift;
  if (ImGui::IsItemActivated()) {
    dragging_ = !translate;
    translating_ = translate;
    drag_angle_deg_ = mouse_angle_deg;
    drag_x_ = m.x;
    drag_y_ = m.y;
  }
  if (ImGui::IsItemActive() && translating_) {
    if (m.x != drag_x_ || m.y != drag_y_) {
      translate_stage(edit, drag_x_, drag_y_, m.x, m.y);
      changed = true;
      drag_x_ = m.x;
      drag_y_ = m.y;
    }
  } else {
    translating_ = false;
  }
  if (ImGui::IsItemActive() && dragging_) {
    double delta = mouse_angle_deg - drag_angle_deg_;
    if (delta > 180) delta -= 360;
    if (delta < -180) delta += 360;
    if (std::abs(delta) > 1e-6 && std::hypot(m.x - c.x, m.y - c.y) > 4.0) {
      edit.stage_deg += delta;
      changed = true;
    }
    drag_angle_deg_ = mouse_angle_deg;
  } else {
    dragging_ = false;
  }
  probe_hovered_ = ImGui::IsItemHovered();
  if (probe_hovered_) {
    probe_x_ = std::clamp((m.x - p0.x) / l.field.w, 0.0f, 1.0f);
    probe_y_ = std::clamp((m.y - p0.y) / l.field.h, 0.0f, 1.0f);
    draw->AddCircle(m, 5, IM_COL32(255, 220, 60, 220), 16, 1.5f);
    draw_grain_overlay(draw, m.x, m.y, 0.18f * r);
    // Ctrl + wheel: the fine focus, 1 um a notch (+ = focusing up), within the scene's travel.
    const ImGuiIO& io = ImGui::GetIO();
    if (io.KeyCtrl && io.MouseWheel != 0.0f) {
      edit.focus_um = std::clamp(edit.focus_um + io.MouseWheel * kFocusStepUm, -kMaxFocusUm, kMaxFocusUm);
      changed = true;
    }
  }

  // Error banner over the top of the field; the scene behind it is the last good one.
  if (!error_.empty()) {
    ImGui::SetCursorScreenPos(ImVec2(l.view.x + 8, l.view.y + 8));
    ImGui::PushStyleColor(ImGuiCol_ChildBg, ImVec4(0.65f, 0.10f, 0.10f, 0.95f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(10, 8));
    ImGui::BeginChild("##error", ImVec2(l.view.w - 16, 72), true, ImGuiWindowFlags_AlwaysUseWindowPadding);
    ImGui::PushTextWrapPos(l.view.w - 110);
    ImGui::TextUnformatted("Not applied, the last good state is kept:");
    ImGui::TextUnformatted(error_.c_str());
    ImGui::PopTextWrapPos();
    ImGui::SetCursorPos(ImVec2(l.view.w - 95, 8));
    if (ImGui::Button("Dismiss")) error_.clear();
    ImGui::EndChild();
    ImGui::PopStyleVar();
    ImGui::PopStyleColor();
  }
  ImGui::End();
  ImGui::PopStyleVar();
}

void App::translate_stage(Scene& edit, float from_x, float from_y, float to_x, float to_y) const {
  // Screen points to image pixels (the field square shows the whole image), then the section
  // point under each: the stage moves by their difference, so the first stays under the cursor.
  const Layout& l = layout_;
  const int w = edit.render.width, h = edit.render.height;
  auto px = [&](float sx, float sy) {
    return section_point_from_pixel(edit, w, h, (sx - l.field.x) / l.field.w * w, (sy - l.field.y) / l.field.h * h);
  };
  const glm::dvec2 d = px(from_x, from_y) - px(to_x, to_y);
  edit.stage.x_mm += d.x;
  edit.stage.y_mm += d.y;
}

void App::draw_scale_bar(ImDrawList* draw) const {
  const Layout& l = layout_;
  const int w = scene_.render.width, h = scene_.render.height;
  const double mm_per_screen_px = mm_per_pixel(scene_, w, h) * w / l.field.w;
  const ScaleBar bar = choose_scale_bar(mm_per_screen_px, static_cast<int>(l.field.w));
  // Inside the circular field stop, low and centred.
  const float len = static_cast<float>(bar.length_px);
  const float x0 = l.field.cx() - len / 2, y0 = l.field.cy() + 0.78f * l.field_radius();
  draw->AddRectFilled(ImVec2(x0 - 1, y0 - 1), ImVec2(x0 + len + 1, y0 + 4), IM_COL32(0, 0, 0, 255));
  draw->AddRectFilled(ImVec2(x0, y0), ImVec2(x0 + len, y0 + 3), IM_COL32(255, 255, 255, 255));
  const ImVec2 ts = ImGui::CalcTextSize(bar.label.c_str());
  const ImVec2 tp(l.field.cx() - ts.x / 2, y0 + 6);
  draw->AddText(ImVec2(tp.x + 1, tp.y + 1), IM_COL32(0, 0, 0, 255), bar.label.c_str());
  draw->AddText(tp, IM_COL32(255, 255, 255, 255), bar.label.c_str());
}

void App::draw_status() {
  const Layout& l = layout_;
  ImGui::SetNextWindowPos(ImVec2(l.status.x, l.status.y));
  ImGui::SetNextWindowSize(ImVec2(l.status.w, l.status.h));
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoBackground);
  const RenderImage& im = image_;
  const bool current = image_current_;
  char err[32] = "err -";  // no estimate yet (a preview, the first pass)
  if (im.error_estimate) std::snprintf(err, sizeof err, "err %.2f dE00", *im.error_estimate);
  ImGui::Text("%s  %.1f spp  %d wl  pass %d  %s  %s  %.0f ms", current ? "" : "(previous)",
              im.samples_per_pixel, im.wavelengths, im.passes, err, im.converged                ? "converged"
              : im.stopped == "cap"       ? "stopped at cap"
              : im.stopped == "cancelled" ? "cancelled"
                                          : "refining",
              im.time_ms);
  ImGui::Text("UI %.1f fps (%.1f ms build)  stage %.1f deg  X %.3f mm  Y %.3f mm  field %.2f mm  %s",
              counters_.fps, counters_.frame_ms, scene_.stage_deg, scene_.stage.x_mm, scene_.stage.y_mm,
              field_of_view_mm(scene_), notice_.c_str());
  if (ImGui::IsWindowHovered() && !im.model_report.empty()) ImGui::SetTooltip("%s", im.model_report.c_str());
  ImGui::End();
}

void App::browse(Browse what) {
  browse_for_ = what;
  if (what == Browse::Scene)
    browser_.open("Open a scene file", resolve_scene_path(scene_path_), {".json"});
  else if (what == Browse::Exercise)
    browser_.open("Open an exercise (<student>.pmexercise.json)", exercise_path_or(scene_path_),
                  {".pmexercise.json"});
  else {
    const std::string current = section_path(scene_.sample.section);
    browser_.open("Open a thin section or EBSD map", current.empty() ? asset_dir() + "/sections/" : current,
                  {".json", ".ctf", ".ang"});
  }
}

void App::draw_file_browser() {
  std::string chosen;
  if (!browser_.draw(chosen)) return;
  if (browse_for_ == Browse::Scene) {
    scene_path_ = chosen;
    load_scene(chosen);
    return;
  }
  if (browse_for_ == Browse::Exercise) {
    open_exercise(chosen);
    return;
  }
  Scene s = scene_;
  s.sample_in = true;
  s.sample.type = SampleType::Section;
  s.sample.section = chosen;
  commit(s);
}

void App::handle_shortcuts(Scene& edit, bool& changed) {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput) return;  // typing a path or a number is not a command
  // Keyboard navigation (F6) owns the keys ImGui navigates with; the other shortcuts stay.
  const bool navigating = (io.ConfigFlags & ImGuiConfigFlags_NavEnableKeyboard) != 0;
  const auto nav_key = [](int key) {
    return key == GLFW_KEY_LEFT || key == GLFW_KEY_RIGHT || key == GLFW_KEY_UP || key == GLFW_KEY_DOWN ||
           key == GLFW_KEY_SPACE || key == GLFW_KEY_ENTER || key == GLFW_KEY_ESCAPE || key == GLFW_KEY_TAB ||
           key == GLFW_KEY_PAGE_UP || key == GLFW_KEY_PAGE_DOWN || key == GLFW_KEY_HOME || key == GLFW_KEY_END;
  };
  for (const Shortcut& s : shortcuts()) {
    if (s.shift != io.KeyShift || s.ctrl != io.KeyCtrl) continue;
    if (navigating && nav_key(s.key)) continue;
    // Turning keys repeat while held, toggles do not (holding A must not flicker the analyzer).
    const bool repeats =
        s.action <= Action::AnalyzerDown || s.action == Action::WedgeIn || s.action == Action::WedgeOut ||
        (s.action >= Action::ViewEast && s.action <= Action::ViewSouth);
    if (ImGui::IsKeyPressed(s.key, repeats)) apply_action(s.action, edit, changed);
  }
}

void App::perform(Action action) {
  Scene edit = scene_;
  bool changed = false;
  apply_action(action, edit, changed);
  if (changed) {
    edit.stage_deg = wrap_deg(edit.stage_deg);
    commit(edit);
  }
}

void App::apply_action(Action action, Scene& edit, bool& changed) {
  auto change = [&] { changed = true; };
  switch (action) {
    case Action::StageCcw:
      edit.stage_deg += 1;
      change();
      break;
    case Action::StageCw:
      edit.stage_deg -= 1;
      change();
      break;
    case Action::StageCcwCoarse:
      edit.stage_deg += 15;
      change();
      break;
    case Action::StageCwCoarse:
      edit.stage_deg -= 15;
      change();
      break;
    case Action::StageZero:
      edit.stage_deg = 0;
      change();
      break;
    case Action::ViewEast:
    case Action::ViewWest:
    case Action::ViewNorth:
    case Action::ViewSouth: {
      // A tenth of the field in the image direction of the arrow, whatever the stage angle.
      const double step = field_of_view_mm(edit) / 10.0;
      const int k = static_cast<int>(action) - static_cast<int>(Action::ViewEast);
      const glm::dvec2 image_step = step * glm::dvec2(k == 0 ? 1 : k == 1 ? -1 : 0, k == 2 ? 1 : k == 3 ? -1 : 0);
      const glm::dvec2 d = StageToSample(edit.stage_deg)(image_step);
      edit.stage.x_mm += d.x;
      edit.stage.y_mm += d.y;
      change();
      break;
    }
    case Action::StageCentre:
      edit.stage.x_mm = edit.stage.y_mm = 0.0;
      change();
      break;
    case Action::PolarizerUp:
      edit.polarizer_deg = wrap_deg(edit.polarizer_deg + 5);
      change();
      break;
    case Action::PolarizerDown:
      edit.polarizer_deg = wrap_deg(edit.polarizer_deg - 5);
      change();
      break;
    case Action::FocusUp:
    case Action::FocusDown:
      edit.focus_um = std::clamp(edit.focus_um + (action == Action::FocusUp ? kFocusStepUm : -kFocusStepUm),
                                 -kMaxFocusUm, kMaxFocusUm);
      change();
      break;
    case Action::AnalyzerUp:
      edit.analyzer_deg = wrap_deg(edit.analyzer_deg + 5);
      change();
      break;
    case Action::AnalyzerDown:
      edit.analyzer_deg = wrap_deg(edit.analyzer_deg - 5);
      change();
      break;
    case Action::ToggleAnalyzer:
      edit.analyzer_in = !edit.analyzer_in;
      change();
      break;
    case Action::CrossPolars:
      edit.analyzer_in = true;
      edit.analyzer_deg = wrap_deg(edit.polarizer_deg + 90);
      change();
      break;
    case Action::ToggleConoscopic: {
      // Condenser top lens and Bertrand lens go in and out together, as `--set mode=` does.
      const bool cono = edit.mode != ViewMode::Cono;
      edit.mode = cono ? ViewMode::Cono : ViewMode::Ortho;
      edit.bertrand_in = cono;
      change();
      break;
    }
    case Action::ToggleBertrand:
      edit.bertrand_in = !edit.bertrand_in;
      change();
      break;
    case Action::CycleCompensator:
      edit.compensator = static_cast<Compensator>((static_cast<int>(edit.compensator) + 1) % 4);
      change();
      break;
    case Action::WedgeIn:
      edit.compensator = Compensator::QuartzWedge;
      edit.compensator_position = std::min(1.0, edit.compensator_position + 0.05);
      change();
      break;
    case Action::WedgeOut:
      edit.compensator = Compensator::QuartzWedge;
      edit.compensator_position = std::max(0.0, edit.compensator_position - 0.05);
      change();
      break;
    case Action::Objective4:
    case Action::Objective10:
    case Action::Objective40:
    case Action::Objective50: {
      const auto& o = kObjectives[static_cast<int>(action) - static_cast<int>(Action::Objective4)];
      edit.objective.magnification = o.magnification;
      edit.objective.na = o.na;
      change();
      break;
    }
    case Action::ToggleIlluminant:
      edit.illuminant = edit.illuminant == Illuminant::D65 ? Illuminant::A : Illuminant::D65;
      change();
      break;
    case Action::ToggleSample:
      edit.sample_in = !edit.sample_in;
      change();
      break;
    case Action::ToggleHelp:
      help_open_ = !help_open_;
      break;
    case Action::ExportField:
      export_field(field_path_);
      break;
    case Action::ExportWindow:
      request_window_screenshot(window_path_);
      break;
    case Action::SaveScene:
      save_scene(scene_path_);
      break;
    case Action::LoadScene:
      load_scene(scene_path_);
      break;
    case Action::ExerciseFocus:
    case Action::ExerciseCheck:
    case Action::ExerciseSave:
    case Action::ExerciseReveal:
      exercise_action(action);
      break;
    case Action::ToggleKeyboardNav: {
      ImGuiIO& io = ImGui::GetIO();
      io.ConfigFlags ^= ImGuiConfigFlags_NavEnableKeyboard;
      const bool on = (io.ConfigFlags & ImGuiConfigFlags_NavEnableKeyboard) != 0;
      // Focus the controls so that the first arrow lands on a widget.
      if (on) ImGui::SetWindowFocus("Microscope");
      note(on ? "keyboard navigation on (F6 to leave): arrows move, Space or Enter acts, Ctrl+Tab changes panel"
              : "keyboard navigation off: arrows turn the stage and the polarizer again");
      break;
    }
  }
}

}  // namespace pmsim::ui
