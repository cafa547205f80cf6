#include "render/gl_api.h"

#include "render/gl_context.h"
#include "sim/error.h"

namespace gs::render {

void GLApi::load(const GLContext& ctx) {
#define GS_GL_LOAD(type, name)                         \
  name = reinterpret_cast<type>(ctx.proc("gl" #name)); \
  if (!name)                                           \
    throw UserError(std::string("the ") + ctx.backend_name() + " OpenGL driver lacks gl" #name);
  GS_GL_FUNCTIONS(GS_GL_LOAD)
#undef GS_GL_LOAD
}

}  // namespace gs::render
