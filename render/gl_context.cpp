#include "render/gl_context.h"

#include <cstdlib>

#include "sim/error.h"

namespace gs::render {

Backend parse_backend(const std::string& name) {
  if (name == "auto") return Backend::Auto;
  if (name == "osmesa") return Backend::OSMesa;
  if (name == "egl") return Backend::EGL;
  throw UsageError("unknown --gl '" + name + "' (use auto, osmesa or egl)");
}

std::unique_ptr<GLContext> GLContext::create(Backend backend) {
  if (backend == Backend::Auto)
    if (const char* env = std::getenv("GRAINSHOCK_GL"); env && *env) backend = parse_backend(env);
  std::string why_osmesa, why_egl;
  if (backend != Backend::EGL)
    if (auto c = create_osmesa_context(why_osmesa)) return c;
  if (backend != Backend::OSMesa)
    if (auto c = create_egl_context(why_egl)) return c;
  std::string why;
  if (!why_osmesa.empty()) why += "OSMesa: " + why_osmesa;
  if (!why_egl.empty()) why += (why.empty() ? "" : "; ") + std::string("EGL: ") + why_egl;
  throw UserError("no usable OpenGL 3.3 core context (" + why + ")");
}

}  // namespace gs::render
