// EGL on Mesa's surfaceless platform: no display server and no pbuffer, only FBOs.
#include "render/gl_context.h"

#ifdef GRAINSHOCK_HAVE_EGL
#include <EGL/egl.h>
#include <EGL/eglext.h>
#endif

namespace gs::render {

#ifdef GRAINSHOCK_HAVE_EGL
namespace {

class EGLContextImpl final : public GLContext {
 public:
  EGLContextImpl(EGLDisplay dpy, EGLContext ctx) : dpy_(dpy), ctx_(ctx) {}
  ~EGLContextImpl() override {
    eglMakeCurrent(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    // No eglTerminate: the surfaceless display is one per process and another renderer may
    // still be using it; terminating is not reference-counted.
    eglDestroyContext(dpy_, ctx_);
  }
  bool bind() { return eglMakeCurrent(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_); }
  void* proc(const char* name) const override {
    return reinterpret_cast<void*>(eglGetProcAddress(name));
  }
  void make_current() override { bind(); }
  const char* backend_name() const override { return "egl"; }

 private:
  EGLDisplay dpy_;
  EGLContext ctx_;
};

}  // namespace

std::unique_ptr<GLContext> create_egl_context(std::string& why) {
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_display) {
    why = "no eglGetPlatformDisplayEXT";
    return nullptr;
  }
  EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
    why = "no surfaceless display";
    return nullptr;
  }
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                            3,
                            EGL_CONTEXT_MINOR_VERSION,
                            3,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                            EGL_NONE};
  EGLContext ctx = EGL_NO_CONTEXT;
  if (eglBindAPI(EGL_OPENGL_API))
    ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (ctx == EGL_NO_CONTEXT) {
    why = "eglCreateContext refused a 3.3 core context";
    return nullptr;
  }
  auto c = std::make_unique<EGLContextImpl>(dpy, ctx);
  if (!c->bind()) {
    why = "eglMakeCurrent without a surface failed";
    return nullptr;
  }
  return c;
}

#else

std::unique_ptr<GLContext> create_egl_context(std::string& why) {
  why = "built without EGL";
  return nullptr;
}

#endif

}  // namespace gs::render
