#pragma once
// ui.scale: the size of the whole interface — text, widgets and the side panels — for classrooms,
// projectors and high-density monitors (issue 23). "auto" (the default) follows the monitor's
// content scale as GLFW reports it (1 off-screen); a number in [0.5, 3] sets it. Set it with
// `pmsim --set ui.scale=1.5`, a script's `set ui.scale=…`, or the Quality tab.
#include <optional>
#include <string>
#include <string_view>

struct ImGuiStyle;

namespace pmsim::ui {

constexpr double kUiScaleMin = 0.5, kUiScaleMax = 3.0;

// The value of ui.scale: a number in range, or nullopt for "auto". Throws InputError (key
// "ui.scale") for anything else.
std::optional<double> parse_ui_scale(std::string_view value);
// Whether an assignment "key=value" is for the UI rather than the scene ("ui.…").
bool is_ui_setting(std::string_view assignment);

// Scales the current ImGui context from `base` (the unscaled style): sizes, paddings and the font.
void apply_ui_scale(const ImGuiStyle& base, float scale);

}  // namespace pmsim::ui
