#pragma once
// Snapshots in, RGBA image out. One Renderer owns one GL context and reuses its programs,
// buffers and framebuffers across calls, so a movie pays the set-up once.
#include <memory>
#include <utility>
#include <vector>

#include "render/camera.h"
#include "render/gl_context.h"
#include "render/image.h"
#include "render/overlay.h"
#include "render/scene.h"
#include "render/style.h"
#include "render/view.h"
#include "sim/snapshot.h"

namespace gs::render {

// What the last render() decided, for callers that want to hold it fixed across frames (a
// movie's colour range) and for tests that look for things in the picture.
struct RenderInfo {
  std::pair<double, double> range{0, 1};  // colour range actually used (single snapshot)
  std::size_t drawn = 0;                  // particles that survived culling
  Camera camera;
  BarRect colorbar;          // empty if none was drawn
  Rect inset;                // empty if none was drawn
  std::vector<Rect> panels;  // every overlay's panel (what a measure of the scene leaves out)
  double v_rms = 0;          // the scale of a scaled field
  // The smallest drawn disc's radius in pixels (3D: at the orbit centre's distance), 0 when
  // nothing was drawn: below 1.5 px a golden comparison cannot see one particle move.
  double disc_radius_px = 0;
};

class Renderer {
 public:
  // UserError if no GL context can be had.
  explicit Renderer(Backend backend = Backend::Auto);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // One snapshot: coloured by style.field. Several: the Fig. 1(a) overlay, each snapshot in its
  // own colour with a legend of times. All must share the dimension. UserError for sizes out
  // of range, an unknown colormap, MIN >= MAX, or a field the snapshot lacks.
  Image render(const std::vector<const Snapshot*>& snaps, const Style& style, const View& view);
  Image render(const Snapshot& s, const Style& style, const View& view) {
    return render(std::vector<const Snapshot*>{&s}, style, view);
  }

  // The steps of render(): the scene (CPU only; the painter measures the overlays) and its
  // picture without overlays.
  Scene scene(const std::vector<const Snapshot*>& snaps, const Style& style, const View& view);
  Image draw(const Scene& scene);

  // Hands back a picture the caller is done with, so that the next one reuses its memory (an
  // 8 MB 1080p picture on fresh pages costs a frame about 2000 page faults). Optional.
  void recycle(Image&& done);

  const RenderInfo& last() const;
  // Largest width or height this context can render (and at most kMaxImageSide).
  int max_size() const;
  const char* backend_name() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The largest width or height of a picture or movie frame any command accepts; a context may
// allow less (Renderer::max_size).
inline constexpr int kMaxImageSide = 16384;

// Throws UserError unless 0 < width, height <= limit.
void check_size(int width, int height, int limit = kMaxImageSide);

}  // namespace gs::render
