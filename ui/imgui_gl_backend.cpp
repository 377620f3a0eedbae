#include "ui/imgui_gl_backend.h"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

// From libimgui's loader (imgui_impl_opengl3_loader.h): fills its GL function table.
extern "C" int imgl3wInit2(void (*(*proc)(const char*))());

#if PMSIM_HAVE_OSMESA
bool pmsim_osmesa_ImGui_ImplOpenGL3_Init(const char* glsl_version);
void pmsim_osmesa_ImGui_ImplOpenGL3_Shutdown();
void pmsim_osmesa_ImGui_ImplOpenGL3_NewFrame();
void pmsim_osmesa_ImGui_ImplOpenGL3_RenderDrawData(ImDrawData* draw_data);
#endif

namespace pmsim::ui {

ImGuiGlBackend prebuilt_imgui_gl_backend() {
  return {ImGui_ImplOpenGL3_Init, ImGui_ImplOpenGL3_Shutdown, ImGui_ImplOpenGL3_NewFrame,
          ImGui_ImplOpenGL3_RenderDrawData};
}

ImGuiGlBackend osmesa_imgui_gl_backend([[maybe_unused]] GlProcLoader loader, bool& available) {
#if PMSIM_HAVE_OSMESA
  available = imgl3wInit2(loader) == 0;
  return {pmsim_osmesa_ImGui_ImplOpenGL3_Init, pmsim_osmesa_ImGui_ImplOpenGL3_Shutdown,
          pmsim_osmesa_ImGui_ImplOpenGL3_NewFrame, pmsim_osmesa_ImGui_ImplOpenGL3_RenderDrawData};
#else
  available = false;
  return {};
#endif
}

}  // namespace pmsim::ui
