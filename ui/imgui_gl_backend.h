#pragma once
// ImGui's OpenGL3 renderer backend, chosen per context: the prebuilt one from libimgui (its
// loader finds GL through libglvnd: GLFW windows and EGL contexts), or the same source compiled
// against OSMesa's entry points for the OSMesa fallback.
#include <string>

#include "ui/gl_functions.h"

struct ImDrawData;

namespace pmsim::ui {

struct ImGuiGlBackend {
  bool (*init)(const char* glsl_version) = nullptr;
  void (*shutdown)() = nullptr;
  void (*new_frame)() = nullptr;
  void (*render)(ImDrawData* draw_data) = nullptr;
};

ImGuiGlBackend prebuilt_imgui_gl_backend();
// Points ImGui's GL loader at `loader` (OSMesaGetProcAddress) and returns the backend compiled for
// it; `available` is false when the build has no OSMesa fallback.
ImGuiGlBackend osmesa_imgui_gl_backend(GlProcLoader loader, bool& available);

}  // namespace pmsim::ui
