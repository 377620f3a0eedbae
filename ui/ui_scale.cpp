#include "ui/ui_scale.h"

#include <cmath>
#include <cstdlib>

#include <imgui.h>

#include "core/base/input_error.h"

namespace pmsim::ui {

std::optional<double> parse_ui_scale(std::string_view value) {
  const std::string v(value);
  if (v == "auto") return std::nullopt;
  char* end = nullptr;
  const double s = std::strtod(v.c_str(), &end);
  if (v.empty() || *end || !std::isfinite(s) || s < kUiScaleMin || s > kUiScaleMax)
    throw InputError("", "ui.scale", v, "expected auto or a scale in [0.5, 3]");
  return s;
}

bool is_ui_setting(std::string_view assignment) { return assignment.rfind("ui.", 0) == 0; }

void apply_ui_scale(const ImGuiStyle& base, float scale) {
  ImGuiStyle& style = ImGui::GetStyle();
  style = base;
  style.ScaleAllSizes(scale);
  // The atlas is rasterised once at 14 px; scaling it keeps one atlas for every scale (a 2×
  // projector view is a little soft, never wrong).
  ImGui::GetIO().FontGlobalScale = scale;
}

}  // namespace pmsim::ui
