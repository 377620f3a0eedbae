#include "ui/shortcuts.h"

#include <algorithm>
#include <cctype>
#include <utility>

#include <GLFW/glfw3.h>

#include "core/base/text.h"

namespace pmsim::ui {
namespace {

const std::vector<std::pair<const char*, int>>& named_keys() {
  static const std::vector<std::pair<const char*, int>> keys = {
      {"Left", GLFW_KEY_LEFT},   {"Right", GLFW_KEY_RIGHT},    {"Up", GLFW_KEY_UP},
      {"Down", GLFW_KEY_DOWN},   {"PageUp", GLFW_KEY_PAGE_UP}, {"PageDown", GLFW_KEY_PAGE_DOWN},
      {"Home", GLFW_KEY_HOME},   {"End", GLFW_KEY_END},        {"Space", GLFW_KEY_SPACE},
      {"Enter", GLFW_KEY_ENTER}, {"Escape", GLFW_KEY_ESCAPE},  {"Tab", GLFW_KEY_TAB},
      {"Comma", GLFW_KEY_COMMA}, {"Period", GLFW_KEY_PERIOD},  {"F1", GLFW_KEY_F1},
      {"F2", GLFW_KEY_F2},       {"F3", GLFW_KEY_F3},          {"F4", GLFW_KEY_F4},
      {"F6", GLFW_KEY_F6},
  };
  return keys;
}

}  // namespace

const std::vector<Shortcut>& shortcuts() {
  static const std::vector<Shortcut> table = {
      {GLFW_KEY_LEFT, false, false, Action::StageCcw, "rotate stage 1 deg counter-clockwise"},
      {GLFW_KEY_RIGHT, false, false, Action::StageCw, "rotate stage 1 deg clockwise"},
      {GLFW_KEY_LEFT, true, false, Action::StageCcwCoarse, "rotate stage 15 deg counter-clockwise"},
      {GLFW_KEY_RIGHT, true, false, Action::StageCwCoarse, "rotate stage 15 deg clockwise"},
      {GLFW_KEY_0, false, false, Action::StageZero, "stage to 0 deg"},
      {GLFW_KEY_RIGHT, false, true, Action::ViewEast, "move the view right over the section (1/10 field)"},
      {GLFW_KEY_LEFT, false, true, Action::ViewWest, "move the view left over the section (1/10 field)"},
      {GLFW_KEY_UP, false, true, Action::ViewNorth, "move the view up over the section (1/10 field)"},
      {GLFW_KEY_DOWN, false, true, Action::ViewSouth, "move the view down over the section (1/10 field)"},
      {GLFW_KEY_0, false, true, Action::StageCentre, "centre the section under the crosshair (x = y = 0 mm)"},
      {GLFW_KEY_UP, false, false, Action::PolarizerUp, "polarizer +5 deg"},
      {GLFW_KEY_DOWN, false, false, Action::PolarizerDown, "polarizer -5 deg"},
      {GLFW_KEY_UP, true, false, Action::FocusUp, "fine focus up 1 um (also Ctrl + wheel over the field)"},
      {GLFW_KEY_DOWN, true, false, Action::FocusDown, "fine focus down 1 um"},
      {GLFW_KEY_PAGE_UP, false, false, Action::AnalyzerUp, "analyzer +5 deg"},
      {GLFW_KEY_PAGE_DOWN, false, false, Action::AnalyzerDown, "analyzer -5 deg"},
      {GLFW_KEY_A, false, false, Action::ToggleAnalyzer, "analyzer in / out"},
      {GLFW_KEY_X, false, false, Action::CrossPolars, "cross the polars (analyzer = polarizer + 90)"},
      {GLFW_KEY_C, false, false, Action::ToggleConoscopic,
       "orthoscopic / conoscopic (condenser lens + Bertrand)"},
      {GLFW_KEY_B, false, false, Action::ToggleBertrand, "Bertrand lens alone in / out"},
      {GLFW_KEY_G, false, false, Action::CycleCompensator, "compensator: none, gypsum, mica, quartz wedge"},
      {GLFW_KEY_PERIOD, false, false, Action::WedgeIn, "push the quartz wedge in"},
      {GLFW_KEY_COMMA, false, false, Action::WedgeOut, "pull the quartz wedge out"},
      {GLFW_KEY_1, false, false, Action::Objective4, "objective 4x / 0.10"},
      {GLFW_KEY_2, false, false, Action::Objective10, "objective 10x / 0.25"},
      {GLFW_KEY_3, false, false, Action::Objective40, "objective 40x / 0.65"},
      {GLFW_KEY_4, false, false, Action::Objective50, "objective 50x / 0.85"},
      {GLFW_KEY_L, false, false, Action::ToggleIlluminant, "illuminant D65 / A"},
      {GLFW_KEY_S, false, false, Action::ToggleSample, "sample in / out (empty stage)"},
      {GLFW_KEY_F1, false, false, Action::ToggleHelp, "show / hide this help"},
      {GLFW_KEY_F2, false, false, Action::ExportField, "export the field image (path in Files)"},
      {GLFW_KEY_F3, false, false, Action::ExportWindow, "screenshot of the whole window"},
      {GLFW_KEY_S, false, true, Action::SaveScene, "save the scene file (path in Files)"},
      {GLFW_KEY_O, false, true, Action::LoadScene, "load the scene file (path in Files)"},
      {GLFW_KEY_E, false, false, Action::ExerciseFocus,
       "exercise: to the Exercise tab's first empty answer (Tab / Shift+Tab: next / previous answer)"},
      {GLFW_KEY_F4, false, false, Action::ExerciseCheck, "exercise: Check the answers (when the exercise allows)"},
      {GLFW_KEY_E, false, true, Action::ExerciseSave, "exercise: save the answers (<student>.answers.json)"},
      {GLFW_KEY_R, false, false, Action::ExerciseReveal, "exercise: reveal layer on / off (after Check)"},
      {GLFW_KEY_F6, false, false, Action::ToggleKeyboardNav,
       "keyboard navigation of the panels on / off: arrows move between controls, Space or Enter acts, "
       "Ctrl+Tab changes panel (the arrow and Space shortcuts wait meanwhile)"},
  };
  return table;
}

bool parse_key_chord(std::string_view text, int& key, bool& shift, bool& ctrl) {
  shift = ctrl = false;
  std::string rest = std::string(text);
  for (;;) {
    const auto plus = rest.find('+');
    if (plus == std::string::npos || plus + 1 == rest.size()) break;
    const std::string mod = lower_case(rest.substr(0, plus));
    if (mod == "shift")
      shift = true;
    else if (mod == "ctrl")
      ctrl = true;
    else
      return false;
    rest = rest.substr(plus + 1);
  }
  for (const auto& [name, code] : named_keys())
    if (lower_case(name) == lower_case(rest)) return key = code, true;
  if (rest.size() == 1) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(rest[0])));
    if ((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')) return key = c, true;  // GLFW = ASCII
    if (c == ',') return key = GLFW_KEY_COMMA, true;
    if (c == '.') return key = GLFW_KEY_PERIOD, true;
  }
  return false;
}

std::string key_chord_name(int key, bool shift, bool ctrl) {
  std::string name;
  for (const auto& [n, code] : named_keys())
    if (code == key) name = n;
  if (name.empty()) name = std::string(1, static_cast<char>(key));
  // assign(1, c), not = ",": GCC 12 warns falsely (-Wrestrict) on assigning a short literal.
  if (key == GLFW_KEY_COMMA) name.assign(1, ',');
  if (key == GLFW_KEY_PERIOD) name.assign(1, '.');
  return std::string(ctrl ? "Ctrl+" : "") + (shift ? "Shift+" : "") + name;
}

}  // namespace pmsim::ui
