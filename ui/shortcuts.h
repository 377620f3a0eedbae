#pragma once
// Keyboard shortcuts: one table shared by the key handler, the help panel and the script reader
// (`key shift+Left`). Keys are GLFW key codes, which is also how ImGui 1.86 indexes io.KeysDown.
#include <string>
#include <string_view>
#include <vector>

namespace pmsim::ui {

enum class Action {
  StageCcw,
  StageCw,
  StageCcwCoarse,
  StageCwCoarse,
  StageZero,
  ViewEast,
  ViewWest,
  ViewNorth,
  ViewSouth,
  StageCentre,
  PolarizerUp,
  PolarizerDown,
  FocusUp,
  FocusDown,
  AnalyzerUp,
  AnalyzerDown,
  ToggleAnalyzer,
  CrossPolars,
  ToggleConoscopic,
  ToggleBertrand,
  CycleCompensator,
  WedgeIn,
  WedgeOut,
  Objective4,
  Objective10,
  Objective40,
  Objective50,
  ToggleIlluminant,
  ToggleSample,
  ToggleHelp,
  ExportField,
  ExportWindow,
  SaveScene,
  LoadScene,
  ExerciseFocus,   // a class exercise is open (ui/exercise_panel.h): the Exercise tab, first answer
  ExerciseCheck,
  ExerciseSave,
  ExerciseReveal,
  ToggleKeyboardNav,  // the panels' widgets by keyboard: arrows move, Space activates
};

struct Shortcut {
  int key;  // GLFW_KEY_*
  bool shift, ctrl;
  Action action;
  const char* what;  // shown in the help panel
};

const std::vector<Shortcut>& shortcuts();
// "shift+Left", "ctrl+s", "C", "F2", "Space": GLFW key code and modifiers; false if unknown.
bool parse_key_chord(std::string_view text, int& key, bool& shift, bool& ctrl);
std::string key_chord_name(int key, bool shift, bool ctrl);

}  // namespace pmsim::ui
