#include "ui/gl_functions.h"

#include <type_traits>

namespace pmsim::ui {

bool GlFunctions::load(GlProcLoader loader, const char** missing) {
  bool ok = true;
  auto get = [&](auto& fn, const char* name) {
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(loader(name));
    if (!fn && ok) {
      ok = false;
      if (missing) *missing = name;
    }
  };
  get(GenTextures, "glGenTextures");
  get(DeleteTextures, "glDeleteTextures");
  get(BindTexture, "glBindTexture");
  get(TexImage2D, "glTexImage2D");
  get(TexSubImage2D, "glTexSubImage2D");
  get(TexParameteri, "glTexParameteri");
  get(PixelStorei, "glPixelStorei");
  get(ReadPixels, "glReadPixels");
  get(GenFramebuffers, "glGenFramebuffers");
  get(DeleteFramebuffers, "glDeleteFramebuffers");
  get(BindFramebuffer, "glBindFramebuffer");
  get(FramebufferTexture2D, "glFramebufferTexture2D");
  get(CheckFramebufferStatus, "glCheckFramebufferStatus");
  get(Viewport, "glViewport");
  get(ClearColor, "glClearColor");
  get(Clear, "glClear");
  get(Finish, "glFinish");
  get(Scissor, "glScissor");
  get(Enable, "glEnable");
  get(Disable, "glDisable");
  get(GetString, "glGetString");
  get(GetError, "glGetError");
  return ok;
}

GlFunctions& gl() {
  static GlFunctions functions;
  return functions;
}

}  // namespace pmsim::ui
