// OSMesa: Mesa's off-screen interface; llvmpipe renders on the CPU with no display at all.
#include <GL/osmesa.h>

#include <vector>

#include "render/gl_context.h"

namespace gs::render {
namespace {

class OSMesaContextImpl final : public GLContext {
 public:
  explicit OSMesaContextImpl(OSMesaContext ctx) : ctx_(ctx), buffer_(4 * 4 * 4) {}
  ~OSMesaContextImpl() override { OSMesaDestroyContext(ctx_); }
  bool bind() { return OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 4, 4); }
  void* proc(const char* name) const override {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
  }
  void make_current() override { bind(); }
  const char* backend_name() const override { return "osmesa"; }

 private:
  OSMesaContext ctx_;
  std::vector<unsigned char> buffer_;  // a token default framebuffer; we draw into FBOs
};

}  // namespace

std::unique_ptr<GLContext> create_osmesa_context(std::string& why) {
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_ACCUM_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         3,
                         0};
  OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!ctx) {
    why = "OSMesaCreateContextAttribs refused a 3.3 core context";
    return nullptr;
  }
  auto c = std::make_unique<OSMesaContextImpl>(ctx);
  if (!c->bind()) {
    why = "OSMesaMakeCurrent failed";
    return nullptr;
  }
  return c;
}

}  // namespace gs::render
