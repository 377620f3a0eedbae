#pragma once
// The handful of OpenGL 3.3 entry points the UI itself calls (field texture, off-screen
// framebuffer, read-back), resolved at run time through the current context's loader. ImGui's own
// loader covers only what ImGui draws with, and the OSMesa fallback is not reachable through
// libglvnd, so nothing here is linked statically against libGL.
#include <GL/glcorearb.h>

namespace pmsim::ui {

using GlProc = void (*)();
using GlProcLoader = GlProc (*)(const char* name);

struct GlFunctions {
  PFNGLGENTEXTURESPROC GenTextures = nullptr;
  PFNGLDELETETEXTURESPROC DeleteTextures = nullptr;
  PFNGLBINDTEXTUREPROC BindTexture = nullptr;
  PFNGLTEXIMAGE2DPROC TexImage2D = nullptr;
  PFNGLTEXSUBIMAGE2DPROC TexSubImage2D = nullptr;
  PFNGLTEXPARAMETERIPROC TexParameteri = nullptr;
  PFNGLPIXELSTOREIPROC PixelStorei = nullptr;
  PFNGLREADPIXELSPROC ReadPixels = nullptr;
  PFNGLGENFRAMEBUFFERSPROC GenFramebuffers = nullptr;
  PFNGLDELETEFRAMEBUFFERSPROC DeleteFramebuffers = nullptr;
  PFNGLBINDFRAMEBUFFERPROC BindFramebuffer = nullptr;
  PFNGLFRAMEBUFFERTEXTURE2DPROC FramebufferTexture2D = nullptr;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus = nullptr;
  PFNGLVIEWPORTPROC Viewport = nullptr;
  PFNGLCLEARCOLORPROC ClearColor = nullptr;
  PFNGLCLEARPROC Clear = nullptr;
  PFNGLFINISHPROC Finish = nullptr;
  PFNGLSCISSORPROC Scissor = nullptr;
  PFNGLENABLEPROC Enable = nullptr;
  PFNGLDISABLEPROC Disable = nullptr;
  PFNGLGETSTRINGPROC GetString = nullptr;
  PFNGLGETERRORPROC GetError = nullptr;

  // Resolves every entry point; false (and the first missing name in `missing`) if one is absent.
  bool load(GlProcLoader loader, const char** missing = nullptr);
};

// The functions of the context current on this thread (set by whoever made it current).
GlFunctions& gl();

}  // namespace pmsim::ui
