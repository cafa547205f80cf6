#pragma once
// A headless OpenGL (core profile, >= 3.3) context made current on the calling thread. OSMesa is
// the default; EGL surfaceless (Mesa's replacement for OSMesa) serves the same interface.
// Rendering always goes to framebuffer objects, so a context owns no window-sized buffer.
#include <memory>
#include <string>

namespace gs::render {

enum class Backend { Auto, OSMesa, EGL };

// "auto", "osmesa" or "egl"; anything else is a UserError naming the word.
Backend parse_backend(const std::string& name);

class GLContext {
 public:
  virtual ~GLContext() = default;
  // Address of a GL entry point (core or extension), nullptr if absent.
  virtual void* proc(const char* name) const = 0;
  virtual void make_current() = 0;
  virtual const char* backend_name() const = 0;

  // Auto tries OSMesa, then EGL; the environment variable GRAINSHOCK_GL (osmesa|egl) overrides
  // Auto. Throws UserError when no context can be had.
  static std::unique_ptr<GLContext> create(Backend backend = Backend::Auto);
};

// Each backend's factory; they return nullptr and set `why` when their library refuses.
std::unique_ptr<GLContext> create_osmesa_context(std::string& why);
std::unique_ptr<GLContext> create_egl_context(std::string& why);

}  // namespace gs::render
