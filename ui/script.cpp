#include "ui/script.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/base/input_error.h"
#include "core/base/units.h"  // kPi, radians, degrees
#include "ui/exercise_panel.h"
#include "ui/shortcuts.h"

namespace pmsim::ui {
namespace {

struct Arity {
  int min, max;
};
const std::map<std::string, Arity>& verbs() {
  static const std::map<std::string, Arity> table = {
      {"set", {1, 1}},  {"key", {1, 1}},         {"move", {2, 2}},   {"click", {2, 2}},
      {"drag", {4, 5}}, {"turn-stage", {1, 2}}, {"pan", {2, 3}},  {"probe", {2, 2}},  {"type", {1, 1}},
      {"wait", {1, 2}}, {"screenshot", {1, 1}},  {"export", {1, 1}}, {"save", {1, 1}},
      {"load", {1, 1}}, {"expect-error", {0, 0}}, {"exercise", {1, 3}}, {"identify", {1, 2}}};
  return table;
}

double number(const ScriptCommand& c, size_t i, const std::string& file) {
  try {
    size_t used = 0;
    const double v = std::stod(c.args.at(i), &used);
    if (used != c.args[i].size() || !std::isfinite(v)) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    throw InputError(file, "line " + std::to_string(c.line), c.args.at(i), "expected a number");
  }
}

// exercise open FILE | answer TASK [VALUE…] | check | reveal on|off | save | goto TASK | wait
void check_exercise_command(const ScriptCommand& c, const std::string& file, const std::string& line) {
  static const std::map<std::string, Arity> subs = {{"open", {1, 1}}, {"answer", {1, 2}}, {"check", {0, 0}},
                                                    {"reveal", {1, 1}}, {"save", {0, 0}},   {"goto", {1, 1}},
                                                    {"wait", {0, 0}}};
  const std::string where = "line " + std::to_string(c.line);
  const auto s = subs.find(c.args[0]);
  if (s == subs.end())
    throw InputError(file, where, c.args[0], "unknown exercise command (open, answer, check, reveal, save, goto, wait)");
  const int n = static_cast<int>(c.args.size()) - 1;
  if (n < s->second.min || n > s->second.max)
    throw InputError(file, where, line, "wrong number of arguments for 'exercise " + c.args[0] + "'");
  if (c.args[0] == "reveal" && c.args[1] != "on" && c.args[1] != "off")
    throw InputError(file, where, c.args[1], "expected on or off");
}

// identify clear | identify KEY [VALUE…] (the key checked here, the value by core when it runs)
void check_identify_command(const ScriptCommand& c, const std::string& file, const std::string& line) {
  const std::string where = "line " + std::to_string(c.line);
  if (c.args[0] == "clear") {
    if (c.args.size() > 1) throw InputError(file, where, line, "'identify clear' takes no argument");
    return;
  }
  const auto& keys = identify_keys();
  if (std::find(keys.begin(), keys.end(), c.args[0]) == keys.end()) {
    std::string list;
    for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
    throw InputError(file, where, c.args[0], "not an observation (clear, " + list + ")");
  }
}

}  // namespace

std::vector<ScriptCommand> parse_script(const std::string& text, const std::string& file) {
  std::vector<ScriptCommand> commands;
  std::istringstream in(text);
  std::string line;
  int number_of_line = 0;
  while (std::getline(in, line)) {
    ++number_of_line;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    ScriptCommand c;
    c.line = number_of_line;
    if (!(words >> c.verb)) continue;
    auto rest_of_line = [&words] {
      std::string rest;
      std::getline(words, rest);
      const auto first = rest.find_first_not_of(' ');
      const auto last = rest.find_last_not_of(" \t\r");
      return first == std::string::npos ? std::string() : rest.substr(first, last - first + 1);
    };
    if (c.verb == "type") {  // the rest of the line, as typed
      std::string rest;
      std::getline(words, rest);
      const auto first = rest.find_first_not_of(' ');
      c.args.push_back(first == std::string::npos ? "" : rest.substr(first));
    } else if (c.verb == "exercise") {  // exercise answer TASK the rest of the line
      std::string sub, task;
      if (words >> sub) c.args.push_back(sub);
      if (sub == "answer" && words >> task) {
        c.args.push_back(task);
        c.args.push_back(rest_of_line());
      } else {
        for (std::string w; words >> w;) c.args.push_back(w);
      }
    } else if (c.verb == "identify") {  // identify KEY the rest of the line (none: clear KEY)
      std::string key;
      if (words >> key) c.args.push_back(key);
      if (const std::string value = rest_of_line(); !value.empty()) c.args.push_back(value);
    } else {
      for (std::string w; words >> w;) c.args.push_back(w);
    }
    const auto v = verbs().find(c.verb);
    const std::string where = "line " + std::to_string(c.line);
    if (v == verbs().end()) throw InputError(file, where, c.verb, "unknown script command");
    const int n = static_cast<int>(c.args.size());
    if (n < v->second.min || n > v->second.max)
      throw InputError(file, where, line, "wrong number of arguments for '" + c.verb + "'");
    if (c.verb == "key") {
      int key;
      bool shift, ctrl;
      if (!parse_key_chord(c.args[0], key, shift, ctrl))
        throw InputError(file, where, c.args[0], "unknown key (e.g. Left, shift+Right, ctrl+s, C)");
    }
    if (c.verb == "exercise") check_exercise_command(c, file, line);
    if (c.verb == "identify") check_identify_command(c, file, line);
    if (c.verb == "set" && c.args[0].find('=') == std::string::npos)
      throw InputError(file, where, c.args[0], "expected key=value");
    if (c.verb == "wait" && c.args[0] != "converged") number(c, 0, file);
    if (c.verb == "move" || c.verb == "click" || c.verb == "drag" || c.verb == "turn-stage" || c.verb == "pan" ||
        c.verb == "probe")
      for (size_t i = 0; i < c.args.size(); ++i) number(c, i, file);
    if (c.verb == "wait" && c.args.size() == 2) number(c, 1, file);
    commands.push_back(std::move(c));
  }
  return commands;
}

std::vector<ScriptCommand> load_script(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw InputError(path, "", "", "cannot open the script");
  std::stringstream text;
  text << f.rdbuf();
  return parse_script(text.str(), path);
}

bool settle(UiDriver& driver, double timeout_s, int* frames) {
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    driver.frame();
    if (frames) ++*frames;
    if (driver.app().converged()) {
      // The converged image may have arrived in the frame's last snapshot, after the field was
      // laid out: when that was its first upload (no texture yet), only the next frame shows it.
      driver.frame();
      if (frames) ++*frames;
      return true;
    }
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout_s)
      return false;
    driver.app().wait_rendered(0.05);  // let the workers have the cores between frames
  }
}

namespace {

// Frames until `done` (a Check graded, the reveal layer computed for the scene on screen).
template <typename Step, typename Done>
bool frames_until(UiDriver& driver, Step& step, Done done, double timeout_s) {
  const auto start = std::chrono::steady_clock::now();
  while (!done()) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout_s) return false;
    driver.app().wait_rendered(0.01);
    step(1);
  }
  return true;
}

template <typename Step>
void run_exercise_command(UiDriver& driver, const ScriptCommand& c, const std::string& file, Step& step,
                          ScriptResult& result) {
  App& app = driver.app();
  const std::string& sub = c.args[0];
  bool waiting = false;
  if (sub == "open") {
    app.open_exercise(c.args[1]);
  } else if (sub == "answer") {
    app.exercise_answer(c.args[1], c.args.size() > 2 ? c.args[2] : "");
  } else if (sub == "check") {
    waiting = app.exercise_check();
  } else if (sub == "reveal") {
    waiting = app.exercise_reveal(c.args[1] == "on") && c.args[1] == "on";
  } else if (sub == "save") {
    app.exercise_save();
  } else if (sub == "goto") {
    app.exercise_goto(c.args[1]);
  } else if (sub == "wait") {
    waiting = true;
  }
  step(1);
  if (!waiting) return;
  const auto* ex = app.exercise();
  const bool reveal = ex && ex->reveal;
  if (!frames_until(driver, step, [&] { return !app.exercise_checking() && (!reveal || app.exercise_reveal_ready()); }, 300.0)) {
    result.ok = false;
    result.error = file + ": line " + std::to_string(c.line) + ": the exercise's " + (app.exercise_checking() ? "Check" : "reveal layer") +
                   " took longer than 300 s";
  }
  step(1);  // the frame that draws it
}

}  // namespace

ScriptResult run_script(UiDriver& driver, const std::vector<ScriptCommand>& commands,
                        const std::string& file) {
  ScriptResult result;
  App& app = driver.app();
  auto step = [&](int n) {
    for (int i = 0; i < n; ++i) {
      driver.frame();
      ++result.frames;
    }
  };
  // However the script ends, later errors (the user's own) must print as failures again.
  struct ClearExpectation {
    App& app;
    ~ClearExpectation() { app.expect_error(""); }
  } clear_expectation{app};
  const std::string script_name = std::filesystem::path(file).stem().string();
  for (size_t i = 0; i < commands.size(); ++i) {
    const ScriptCommand& c = commands[i];
    const auto& a = c.args;
    auto num = [&](size_t k) { return number(c, k, file); };
    const auto failures_before = app.counters().failures;
    const bool expected = i + 1 < commands.size() && commands[i + 1].verb == "expect-error";
    app.expect_error(expected ? script_name + " line " + std::to_string(c.line) : "");
    if (c.verb == "set") {
      app.set(a[0]);
      step(1);
    } else if (c.verb == "key") {
      int key;
      bool shift, ctrl;
      parse_key_chord(a[0], key, shift, ctrl);
      driver.inject_key(key, shift, ctrl);
      step(2);  // down, then up
    } else if (c.verb == "move") {
      driver.inject_mouse(static_cast<float>(num(0)), static_cast<float>(num(1)), false);
      step(1);
    } else if (c.verb == "probe") {
      const Rect& f = app.layout().field;
      driver.inject_mouse(f.x + static_cast<float>(num(0)) * f.w, f.y + static_cast<float>(num(1)) * f.h,
                          false);
      step(1);
    } else if (c.verb == "click") {
      const auto x = static_cast<float>(num(0)), y = static_cast<float>(num(1));
      driver.inject_mouse(x, y, false);
      step(1);
      driver.inject_mouse(x, y, true);
      step(1);
      driver.inject_mouse(x, y, false);
      step(1);
    } else if (c.verb == "drag" || c.verb == "turn-stage") {
      std::vector<std::pair<float, float>> path;
      if (c.verb == "drag") {
        const int n = a.size() > 4 ? std::max(1, static_cast<int>(num(4))) : 10;
        for (int k = 0; k <= n; ++k) {
          const double t = static_cast<double>(k) / n;
          path.emplace_back(static_cast<float>(num(0) + t * (num(2) - num(0))),
                            static_cast<float>(num(1) + t * (num(3) - num(1))));
        }
      } else {
        // An arc at 0.7 of the field radius, starting east; screen y grows downwards.
        const Rect& f = app.layout().field;
        const double r = 0.35 * f.w, sweep = radians(num(0));
        const int n = a.size() > 1 ? std::max(1, static_cast<int>(num(1))) : 12;
        for (int k = 0; k <= n; ++k) {
          const double angle = sweep * k / n;
          path.emplace_back(static_cast<float>(f.cx() + r * std::cos(angle)),
                            static_cast<float>(f.cy() - r * std::sin(angle)));
        }
      }
      driver.inject_mouse(path.front().first, path.front().second, false);
      step(1);
      for (const auto& [x, y] : path) {
        driver.inject_mouse(x, y, true);
        step(1);
      }
      driver.inject_mouse(path.back().first, path.back().second, false);
      step(1);
    } else if (c.verb == "pan") {
      // A right-button drag from the field centre by (dx, dy) field widths (screen y down): the
      // mechanical stage moves the section with the cursor.
      const Rect& f = app.layout().field;
      const int n = a.size() > 2 ? std::max(1, static_cast<int>(num(2))) : 10;
      driver.inject_mouse(f.cx(), f.cy(), false);
      step(1);
      for (int k = 0; k <= n; ++k) {
        const double t = static_cast<double>(k) / n;
        driver.inject_mouse(static_cast<float>(f.cx() + t * num(0) * f.w),
                            static_cast<float>(f.cy() + t * num(1) * f.h), false, true);
        step(1);
      }
      driver.inject_mouse(static_cast<float>(f.cx() + num(0) * f.w), static_cast<float>(f.cy() + num(1) * f.h),
                          false);
      step(1);
    } else if (c.verb == "type") {
      driver.inject_text(a[0]);
      step(1);
    } else if (c.verb == "wait") {
      if (a[0] == "converged") {
        int frames = 0;
        if (!settle(driver, a.size() > 1 ? num(1) : 600.0, &frames)) {
          result.ok = false;
          result.error = file + ": line " + std::to_string(c.line) + ": the image did not converge in time";
          return result;
        }
        result.frames += frames;
      } else {
        step(std::max(0, static_cast<int>(num(0))));
      }
    } else if (c.verb == "screenshot") {
      app.request_window_screenshot(a[0]);
      step(1);
    } else if (c.verb == "export") {
      app.export_field(a[0]);
      step(1);
    } else if (c.verb == "save") {
      app.save_scene(a[0]);
      step(1);
    } else if (c.verb == "load") {
      app.load_scene(a[0]);
      step(1);
    } else if (c.verb == "exercise") {
      run_exercise_command(driver, c, file, step, result);
      if (!result.ok) return result;
    } else if (c.verb == "identify") {
      if (a[0] == "clear")
        app.identify_clear();
      else
        app.identify_observation(a[0], a.size() > 1 ? a[1] : "");
      step(2);  // the tab comes to the front, then shows the candidates
    } else if (c.verb == "expect-error") {
      continue;  // checked with the command before it
    }
    const bool failed = app.counters().failures != failures_before;
    if (failed != expected) {
      result.ok = false;
      result.error = file + ": line " + std::to_string(c.line) + ": " +
                     (failed ? app.error() : "expected an error, got none");
      return result;
    }
  }
  return result;
}

}  // namespace pmsim::ui
