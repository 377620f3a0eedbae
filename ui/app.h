#pragma once
// The interactive microscope: a thin client over pmsim_core. All state that defines the image is
// one pmsim::Scene; every widget, shortcut, mouse drag and script line edits a copy of it and hands
// the copy to commit(), which validates it, restarts the progressive renderer, or shows the error
// banner and keeps the last good scene. The UI thread never renders: it uploads the renderer's
// latest snapshot into a texture and draws.
#include <cstdint>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/exercise/identify.h"
#include "core/microscope/grain_report.h"
#include "core/microscope/scene.h"
#include "core/render/progressive_renderer.h"
#include "ui/file_browser.h"
#include "ui/layout.h"
#include "ui/render_feed.h"
#include "ui/linear_texture.h"
#include "ui/shortcuts.h"

struct ImDrawList;
struct ImGuiStyle;

namespace pmsim {
class SectionMap;
}

namespace pmsim::ui {

struct ExerciseSession;  // ui/exercise_panel.h

struct AppCounters {
  std::uint64_t frames = 0;    // frames built
  std::uint64_t uploads = 0;   // field texture uploads (new renderer snapshots)
  std::uint64_t commits = 0;   // accepted scene changes
  std::uint64_t rejected = 0;  // scene changes refused (error banner)
  std::uint64_t failures = 0;  // errors shown in the banner (bad input, failed writes)
  // Frames from an accepted change to the first frame showing an image of it (that frame
  // included: 1 = the change's own frame): summed over changes whose image was shown before the
  // next change, and the largest seen.
  std::uint64_t first_images = 0;
  std::uint64_t first_image_frames = 0;
  std::uint64_t first_image_frames_max = 0;
  double frame_ms = 0.0;  // CPU time of the last frame() call
  double fps = 0.0;       // UI frames per second, smoothed (driver-measured)
};

class App {
 public:
  // Needs the GL context current (textures are made on the first frame).
  explicit App(const Scene& scene = {}, int renderer_threads = 0);
  ~App();
  App(const App&) = delete;
  App& operator=(const App&) = delete;

  // One frame of the whole window, between ImGui::NewFrame() and ImGui::Render().
  void frame();
  void set_window_size(int width, int height);
  void set_measured_fps(double fps) { counters_.fps = fps; }
  // ui.scale (ui/ui_scale.h): the monitor's content scale (what "auto" follows; the window driver
  // reports it), the setting (nullopt: auto) and the scale in effect.
  void set_content_scale(float scale);
  void set_ui_scale(std::optional<double> scale);
  float ui_scale() const { return ui_scale_.value_or(content_scale_); }
  std::optional<double> ui_scale_setting() const { return ui_scale_; }

  // --- the one door for state changes -----------------------------------------------------
  bool commit(const Scene& candidate);    // false: banner shown, last good scene kept
  bool set(std::string_view assignment);  // "key=value": scene keys through commit(), and ui.scale
  void perform(Action action);            // what a shortcut does
  bool load_scene(const std::string& path);
  // The file dialog (ui/file_browser.h): a scene file to load, or a thin section / EBSD map to put
  // on the stage. The buttons "Browse..." in the Files and Sample tabs open it.
  enum class Browse { Scene, Section, Exercise };
  void browse(Browse what);
  bool browsing() const { return browser_.is_open(); }
  bool save_scene(const std::string& path);
  bool export_field(const std::string& path);  // .png (sRGB) or .exr/.tif (linear), scene in metadata
  // Whole-window screenshots need the framebuffer after ImGui has drawn; the driver collects
  // the request after rendering and hands the pixels back to write_window_pixels().
  void request_window_screenshot(const std::string& path) { window_shot_ = path; }
  std::optional<std::string> take_window_screenshot_request();
  bool write_window_pixels(const std::string& path, int width, int height,
                           const std::vector<std::uint8_t>& rgb8);

  const Scene& scene() const { return scene_; }
  const RenderImage& image() const { return image_; }
  // The image on screen is the final image of the current scene: converged (estimate below the
  // tolerance) or stopped at its cap (image().stopped says which).
  bool converged() const { return (image_.converged || image_.stopped == "cap") && image_current_; }
  bool image_current() const { return image_current_; }  // on screen: an image of scene()
  bool wait_rendered(double timeout_s) const;            // blocks (drivers/tests only, never in frame())
  const std::string& error() const { return error_; }
  void clear_error() { error_.clear(); }
  // A script that provokes an error on purpose (`expect-error`) names where, e.g. "tour line 57":
  // until cleared with "", errors still raise the banner, but stderr gets one line saying the
  // error was expected instead of what reads as a failure.
  void expect_error(std::string where) {
    expected_error_ = std::move(where);
    expected_error_said_ = false;
  }
  const Layout& layout() const { return layout_; }
  const AppCounters& counters() const { return counters_; }
  bool help_open() const { return help_open_; }
  // The Becke-line sentence the teaching panel shows at the probe (grain mounts, orthoscopic thin
  // sections; empty until the probe has answered, or after an error): what the student reads.
  std::string becke_text() const;

  // --- a class exercise (ui/exercise_panel.cpp, ui/reveal_layer.cpp) ---------------------
  // Opens a student file (<student>.pmexercise.json): its specimen becomes the scene (unless
  // load_specimen is false: the command line has loaded it with its --set changes), its tasks the
  // Exercise tab, the answers saved beside it are read back. False: banner shown.
  bool open_exercise(const std::string& path, bool load_specimen = true);
  // What the student types in the task's answer field (by task id); "" clears it.
  bool exercise_answer(const std::string& task, const std::string& text);
  // Grades the answers against the exercise made again from its template and seed (off the UI
  // thread); false when no exercise is open or its template does not allow checking.
  bool exercise_check();
  bool exercise_checking() const;  // a Check in flight
  // The reveal layer over the field (only after a Check).
  bool exercise_reveal(bool on);
  // The reveal layer is on and shows the current scene (no computation in flight).
  bool exercise_reveal_ready() const;
  bool exercise_save();                         // <student>.answers.json, atomically
  bool exercise_goto(const std::string& task);  // the task's grain under the crosshair
  const ExerciseSession* exercise() const { return exercise_.get(); }

  // --- the Identify tab (ui/identify_panel.cpp): pmsim-exercise identify in the app --------
  // An observation as `pmsim-exercise identify --KEY VALUE` takes it (keys: identify_keys();
  // core/exercise/identify.h parse_observation); "" clears it. False (banner shown, the
  // observation unchanged) for an unknown key or a value core refuses. Brings the tab to the front.
  bool identify_observation(const std::string& key, const std::string& value);
  void identify_clear();  // every observation
  // The library minerals consistent with the observations given (every one when none is), as
  // core's identify() returns them, and the observations as typed (key → text).
  const std::vector<Candidate>& identify_candidates();
  const std::map<std::string, std::string>& identify_observations() const { return identify_.values; }

 private:
  void pull_snapshot();
  void draw_controls(Scene& edit, bool& changed);
  void draw_microscope_tab(Scene& edit, bool& changed);
  void draw_sample_tab(Scene& edit, bool& changed);
  void draw_quality_tab(Scene& edit, bool& changed);
  void draw_files_tab();
  void draw_about_tab();
  void draw_field(Scene& edit, bool& changed);
  void draw_status();
  void draw_scale_bar(ImDrawList* draw) const;
  void draw_slide_overview(Scene& edit, bool& changed);
  void draw_rock_seed(SampleSettings& s, bool& changed);
  void translate_stage(Scene& edit, float from_x, float from_y, float to_x, float to_y) const;
  void draw_chart();
  void draw_teaching();
  void draw_grain_text(const GrainReport& g);
  void draw_grain_overlay(ImDrawList* draw, float cx, float cy, float len) const;
  void draw_help();
  void draw_exercise_tab(Scene& edit, bool& changed);
  void draw_identify_tab();
  void update_identify();
  void draw_exercise_task(int i, Scene& edit, bool& changed);
  void draw_exercise_results();
  void poll_exercise();
  void draw_reveal(ImDrawList* draw) const;
  void draw_task_markers(ImDrawList* draw) const;
  void exercise_action(Action action);
  std::string exercise_path_or(const std::string& fallback) const;
  void handle_shortcuts(Scene& edit, bool& changed);
  void apply_action(Action action, Scene& edit, bool& changed);
  void fail(const std::string& message);
  void note(const std::string& message);

  Scene scene_;                   // the last good scene: what the renderer is rendering
  Scene previous_scene_;          // the one before, restored if the renderer refuses scene_
  std::uint64_t generation_ = 0;  // counts accepted scenes (the feed's submission ids)
  std::unique_ptr<RenderFeed> feed_;
  RenderImage image_;
  bool image_current_ = false;                 // image_ belongs to scene_
  std::optional<std::uint64_t> change_frame_;  // counters_.frames at the last change not yet shown
  LinearTexture field_texture_;
  Layout layout_;
  int window_w_ = 1280, window_h_ = 800;
  float content_scale_ = 1.0f;
  std::optional<float> ui_scale_;
  float ui_scale_edit_ = 0.0f;  // the Quality tab's slider while it is dragged
  std::unique_ptr<ImGuiStyle> base_style_;  // the unscaled style, as the driver set it up
  void apply_scale();
  AppCounters counters_;

  std::string error_;   // banner text; "" = no banner
  std::string expected_error_;  // where a script expects the next error; "" = none expected
  bool expected_error_said_ = false;
  std::string notice_;  // last success message (exports, saves)
  bool help_open_ = false;
  bool reticle_ = true;
  bool scale_bar_ = true;
  bool grain_overlay_ = true;  // vibration directions and cleavage of the grain at the probe  // over the field and in field exports (orthoscopic view)
  bool dragging_ = false;
  bool translating_ = false;  // right button or Shift + left: the stage translates
  float drag_x_ = 0, drag_y_ = 0;
  double drag_angle_deg_ = 0.0;
  float probe_x_ = 0.5f, probe_y_ = 0.5f;  // cursor on the field, fractions from the top left
  bool probe_hovered_ = false;
  std::optional<std::string> window_shot_;
  std::string scene_path_ = "pmsim-scene.json";
  std::string field_path_ = "pmsim-field.png";
  std::string window_path_ = "pmsim-window.png";

  FileBrowser browser_;
  Browse browse_for_ = Browse::Scene;
  void draw_file_browser();

  std::unique_ptr<ExerciseSession> exercise_;

  struct IdentifyState {
    std::map<std::string, std::string> values;  // key → the text typed or the word chosen
    std::map<std::string, std::string> errors;  // key → why core refuses the text (left out until fixed)
    std::vector<Candidate> candidates;
    bool stale = true;        // values changed since `candidates` were computed
    bool select_tab = false;  // bring the Identify tab to the front on the next frame
  };
  IdentifyState identify_;

  struct Teaching;  // cursor probe, chart and figure text (teaching_panel.cpp)
  std::unique_ptr<Teaching> teaching_;

  // The slide overview's section, loaded off the UI thread: a rock grown from its recipe takes
  // seconds the first time (sample.section, sample.seed), and the window must keep drawing.
  struct SlideSection {
    std::string key;  // the section, seed and orientation seed it is for
    std::future<std::shared_ptr<const SectionMap>> job;
    std::shared_ptr<const SectionMap> map;
    bool failed = false;
  };
  SlideSection slide_;
};

// The observation keys of pmsim-exercise identify (and the script's `identify KEY VALUE`).
const std::vector<std::string>& identify_keys();

// Wrap an angle into [0, 360).
double wrap_deg(double angle_deg);

}  // namespace pmsim::ui
