#include "ui/cli.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/io/cli_policy.h"
#include "core/base/input_error.h"
#include "core/io/scene_file.h"
#include "ui/asset_lists.h"
#include "ui/headless_driver.h"
#include "ui/script.h"
#include "ui/ui_scale.h"
#include "ui/window_driver.h"

namespace pmsim::ui {
namespace {

constexpr const char* kProgram = "pmsim";

struct Options {
  std::string scene_file;
  std::vector<std::string> sets;
  bool headless = false;
  int frames = -1;
  std::string script, screenshot;
  bool settle = true, report_fps = false;
  double timeout_s = 600;
  int width = 1280, height = 800, threads = 0;
};

[[noreturn]] void bad(const std::string& message) { cli::usage_error(kProgram, message); }

int to_int(const std::string& flag, const std::string& v) {
  try {
    size_t used = 0;
    const int n = std::stoi(v, &used);
    if (used == v.size() && n >= 0) return n;
  } catch (const std::exception&) {
  }
  bad(flag + " " + v + ": expected a non-negative integer");
}

Options parse(int argc, char** argv) {
  Options o;
  std::string frames, threads, timeout, size;
  CLI::App app{"pmsim - interactive polarizing microscope", kProgram};
  app.footer(
      "Without SCENE, starts on the granite thin section between crossed polars\n"
      "(assets/scenes/quartz_section_ortho.json, the default scene of pmsim-render).");
  cli::last_value_wins(app);
  app.add_option("SCENE", o.scene_file, "scene file (JSON)")->type_name("FILE.json");
  app.add_flag("--headless", o.headless,
               "draw the window off-screen (EGL surfaceless, else OSMesa), no display needed");
  cli::add_repeatable(app, "--set", o.sets, "change a scene key (repeatable; keys as in pmsim-render), or ui.scale=auto|0.5…3 (the interface's size)")
      ->type_name("key=value");
  app.add_option("--frames", frames,
                 "run N frames (windowed: then quit; headless: before settling, default 3)")
      ->type_name("N");
  app.add_option("--script", o.script, "replay user actions (format: assets/ui/README.md)")
      ->type_name("FILE");
  app.add_option("--screenshot", o.screenshot,
                 "write the whole window as PNG at the end (headless: after convergence)")
      ->type_name("FILE");
  bool no_settle = false;
  app.add_flag("--no-settle", no_settle,
               "headless: do not wait for the image to converge before the screenshot");
  app.add_option("--timeout", timeout,
                 "headless: give up waiting for convergence after S seconds (default 600)")
      ->type_name("S");
  app.add_option("--size", size, "window size (default 1280x800)")->type_name("WxH");
  app.add_option("--threads", threads, "renderer worker threads (default: all cores)")->type_name("N");
  app.add_flag("--report-fps", o.report_fps, "print the UI frame rate measured over the run");
  cli::parse_or_exit(app, argc, argv);
  o.settle = !no_settle;
  // Numbers are read as text and converted by to_int: non-negative integers only.
  if (app.count("--frames")) o.frames = to_int("--frames", frames);
  if (app.count("--threads")) o.threads = to_int("--threads", threads);
  if (app.count("--timeout")) o.timeout_s = to_int("--timeout", timeout);
  if (app.count("--size")) {
    const std::string& v = size;
    const auto x = v.find('x');
    if (x == std::string::npos) bad("--size " + v + ": expected WxH");
    o.width = to_int("--size", v.substr(0, x));
    o.height = to_int("--size", v.substr(x + 1));
    if (o.width < 320 || o.height < 240) bad("--size " + v + ": at least 320x240");
  }
  if (o.headless && o.screenshot.empty() && o.script.empty() && !o.report_fps)
    bad("--headless needs --screenshot FILE.png, --script FILE or --report-fps");
  return o;
}

void report(const UiDriver& d) {
  const FrameTimes& t = d.frame_times();
  std::printf("ui_fps=%.1f frames=%zu mean_ms=%.2f p50_ms=%.2f p95_ms=%.2f size=%dx%d gl=%s\n", t.fps(),
              t.ms.size(), t.mean_ms(), t.percentile_ms(0.5), t.percentile_ms(0.95), d.width(), d.height(),
              d.gl_name());
}

}  // namespace

int pmsim_main(int argc, char** argv) {
  const Options o = parse(argc, argv);

  // All input is checked before any window opens: bad input is exit 2 with nothing written.
  Scene scene;
  std::vector<ScriptCommand> script;
  std::optional<double> ui_scale;  // --set ui.scale (nullopt: auto)
  // The built-in Scene{} is a plate at extinction (a black field); a first look should show
  // something: the thin section pmsim-render renders by default.
  std::string scene_file = o.scene_file;
  if (scene_file.empty()) {
    const std::string fallback = asset_dir() + "/scenes/quartz_section_ortho.json";
    std::error_code ec;
    if (std::filesystem::exists(fallback, ec)) scene_file = fallback;
  }
  try {
    if (!scene_file.empty()) {
      std::vector<std::string> warnings;
      scene = load_scene_file(scene_file, &warnings);
      for (const auto& w : warnings) std::cerr << "pmsim: warning: " << w << "\n";
    }
    // ui.* keys set the interface, not the scene: checked here, applied once the app exists.
    std::vector<std::string> scene_sets;
    for (const std::string& a : o.sets) {
      if (!is_ui_setting(a)) {
        scene_sets.push_back(a);
        continue;
      }
      const auto eq = a.find('=');
      if (a.substr(0, eq) != "ui.scale")
        throw InputError("", a.substr(0, eq), eq == std::string::npos ? "" : a.substr(eq + 1),
                         "unknown key (the UI's keys: ui.scale)");
      ui_scale = parse_ui_scale(eq == std::string::npos ? "" : a.substr(eq + 1));
    }
    apply_settings(scene, scene_sets);
    validate_scene(scene, scene_file);
    if (!o.script.empty()) script = load_script(o.script);
  } catch (const InputError& e) {
    std::cerr << "pmsim: " << e.what() << "\n";
    return 2;
  }

  std::string log;
  std::unique_ptr<UiDriver> driver;
  if (o.headless)
    driver = HeadlessDriver::create(scene, o.width, o.height, log, o.threads);
  else
    driver = WindowDriver::create(scene, o.width, o.height, log, o.threads);
  if (!driver) {
    std::cerr << "pmsim: no usable OpenGL:\n" << log;
    if (!o.headless) std::cerr << "pmsim: without a display, try: pmsim --headless --screenshot out.png\n";
    return 1;
  }
  if (!log.empty()) std::cerr << log;
  if (ui_scale) driver->app().set_ui_scale(ui_scale);

  int status = 0;
  // A student's exercise file: its specimen is the scene loaded above; its tasks open in the
  // Exercise tab (ui/exercise_panel.h).
  if (scene_file.ends_with(".pmexercise.json") && !driver->app().open_exercise(scene_file, false)) status = 2;
  if (!script.empty()) {
    const ScriptResult r = run_script(*driver, script, o.script);
    if (!r.ok) {
      std::cerr << "pmsim: " << r.error << "\n";
      status = 2;
    }
  }
  if (o.headless) {
    for (int i = 0; i < (o.frames >= 0 ? o.frames : 3); ++i) driver->frame();
    if (!o.screenshot.empty() && o.settle && !settle(*driver, o.timeout_s))
      std::cerr << "pmsim: warning: the image had not converged after " << o.timeout_s << " s\n";
  } else {
    for (int n = 0; o.frames < 0 || n < o.frames; ++n)
      if (!driver->frame()) break;
  }
  if (!o.screenshot.empty()) {
    driver->app().request_window_screenshot(o.screenshot);
    const auto failures = driver->app().counters().failures;
    driver->frame();
    if (driver->app().counters().failures != failures) status = 2;
  }
  if (o.report_fps) report(*driver);
  return status;
}

}  // namespace pmsim::ui
