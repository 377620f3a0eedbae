#include "ui/offscreen_context.h"

#include <cstdlib>
#include <cstring>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#if PMSIM_HAVE_OSMESA
#include <GL/osmesa.h>
#endif
#include <GL/glcorearb.h>

namespace pmsim::ui {
namespace {

GlProc egl_proc(const char* name) { return reinterpret_cast<GlProc>(eglGetProcAddress(name)); }

#if PMSIM_HAVE_OSMESA
GlProc osmesa_proc(const char* name) { return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name)); }
#endif

}  // namespace

std::unique_ptr<OffscreenContext> OffscreenContext::create(int width, int height, std::string& log) {
  std::unique_ptr<OffscreenContext> ctx(new OffscreenContext());
  ctx->width_ = width;
  ctx->height_ = height;
  const char* forced = std::getenv("PMSIM_GL");
  const std::string force = forced ? forced : "";
  if (force != "osmesa" && ctx->try_egl(log) && ctx->create_framebuffer(log)) return ctx;
  if (force != "egl" && ctx->try_osmesa(log) && ctx->create_framebuffer(log)) return ctx;
  return nullptr;
}

bool OffscreenContext::try_egl(std::string& log) {
  EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
    log += "EGL: no surfaceless Mesa display\n";
    return false;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    log += "EGL: OpenGL API not available\n";
    eglTerminate(display);
    return false;
  }
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE,
                                   EGL_PBUFFER_BIT,
                                   EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT,
                                   EGL_RED_SIZE,
                                   8,
                                   EGL_GREEN_SIZE,
                                   8,
                                   EGL_BLUE_SIZE,
                                   8,
                                   EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglChooseConfig(display, config_attribs, &config, 1, &count) || count < 1) {
    log += "EGL: no OpenGL config\n";
    eglTerminate(display);
    return false;
  }
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                    3,
                                    EGL_CONTEXT_MINOR_VERSION,
                                    3,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
  if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    log += "EGL: cannot create or bind a 3.3 core context without a surface\n";
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
    return false;
  }
  egl_display_ = display;
  egl_context_ = context;
  const char* missing = nullptr;
  if (!gl().load(egl_proc, &missing)) {
    log += std::string("EGL: missing GL entry point ") + missing + "\n";
    return false;
  }
  api_ = OffscreenApi::EglSurfaceless;
  backend_ = prebuilt_imgui_gl_backend();
  return true;
}

bool OffscreenContext::try_osmesa(std::string& log) {
#if PMSIM_HAVE_OSMESA
  if (egl_context_) {
    eglMakeCurrent(egl_display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(egl_display_, egl_context_);
    eglTerminate(egl_display_);
    egl_context_ = egl_display_ = nullptr;
  }
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         3,
                         0};
  OSMesaContext context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!context) {
    log += "OSMesa: cannot create a 3.3 core context\n";
    return false;
  }
  osmesa_context_ = context;
  osmesa_buffer_.assign(static_cast<size_t>(width_) * height_ * 4, 0);
  if (!OSMesaMakeCurrent(context, osmesa_buffer_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
    log += "OSMesa: cannot make the context current\n";
    return false;
  }
  const char* missing = nullptr;
  if (!gl().load(osmesa_proc, &missing)) {
    log += std::string("OSMesa: missing GL entry point ") + missing + "\n";
    return false;
  }
  bool available = false;
  backend_ = osmesa_imgui_gl_backend(osmesa_proc, available);
  if (!available) {
    log += "OSMesa: ImGui's GL loader rejected the context\n";
    return false;
  }
  api_ = OffscreenApi::OSMesa;
  return true;
#else
  log += "OSMesa: not built in\n";
  return false;
#endif
}

bool OffscreenContext::create_framebuffer(std::string& log) {
  GlFunctions& g = gl();
  g.GenTextures(1, &color_);
  g.BindTexture(GL_TEXTURE_2D, color_);
  g.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width_, height_, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  g.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  g.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  g.GenFramebuffers(1, &fbo_);
  g.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  g.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_, 0);
  if (g.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    log += std::string(api_name()) + ": framebuffer object incomplete\n";
    return false;
  }
  g.Viewport(0, 0, width_, height_);
  return true;
}

OffscreenContext::~OffscreenContext() {
  if (fbo_ && (egl_context_ || osmesa_context_)) {
    gl().DeleteFramebuffers(1, &fbo_);
    gl().DeleteTextures(1, &color_);
  }
  if (egl_context_) {
    eglMakeCurrent(egl_display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(egl_display_, egl_context_);
    eglTerminate(egl_display_);
  }
#if PMSIM_HAVE_OSMESA
  if (osmesa_context_) OSMesaDestroyContext(static_cast<OSMesaContext>(osmesa_context_));
#endif
}

const char* OffscreenContext::api_name() const {
  return api_ == OffscreenApi::OSMesa ? "OSMesa" : "EGL surfaceless";
}

void OffscreenContext::bind_framebuffer() {
  gl().BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl().Viewport(0, 0, width_, height_);
}

std::vector<std::uint8_t> OffscreenContext::read_rgb8() {
  GlFunctions& g = gl();
  bind_framebuffer();
  g.Finish();
  std::vector<std::uint8_t> rgba(static_cast<size_t>(width_) * height_ * 4);
  g.PixelStorei(GL_PACK_ALIGNMENT, 1);
  g.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  // GL rows start at the bottom; images start at the top.
  std::vector<std::uint8_t> rgb(static_cast<size_t>(width_) * height_ * 3);
  for (int y = 0; y < height_; ++y) {
    const std::uint8_t* src = &rgba[static_cast<size_t>(height_ - 1 - y) * width_ * 4];
    std::uint8_t* dst = &rgb[static_cast<size_t>(y) * width_ * 3];
    for (int x = 0; x < width_; ++x) std::memcpy(dst + 3 * x, src + 4 * x, 3);
  }
  return rgb;
}

}  // namespace pmsim::ui
