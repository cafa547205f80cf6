#include "render/renderer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <string>

#include "render/annotations.h"
#include "render/colormap.h"
#include "render/field.h"
#include "render/frame_threads.h"
#include "render/gl_api.h"
#include "render/shader_files.h"
#include "sim/error.h"

namespace gs::render {
namespace {

// What the CPU splats keep from frame to frame (filled anew each frame, never shrunk), so that a
// movie's frames touch no fresh pages.
// The coverage of one disc radius at kPhases x kPhases sub-pixel positions of the centre, for
// the splats: the rule of splat_disc (coverage from the distance to the rim) evaluated once per
// frame at the middle of each phase cell and kept as 8 bits, so that a disc costs table reads
// and integer blends instead of a square root and float blends per pixel.
constexpr int kPhases = 32;
struct Stamps {
  float r = -1;  // world radius of the discs (with ppu: the pixel radius)
  double ppu = 0;
  int lo = 0, size = 0;  // pixels lo .. lo + size - 1 from the centre's pixel, in x and in y
  // Per phase (y major): the box of pixels with coverage > 0, offsets from lo.
  std::vector<std::array<std::uint8_t, 4>> box;  // x0, x1, y0, y1 (inclusive; x0 > x1: none)
  std::vector<std::uint8_t> alpha;               // per phase, size x size, row major; 0..255
};

// A disc as a band list holds it: a stamped disc by the pixel its centre falls in, its phase,
// the thread's slot of its radius and its colour, worked out once when it is binned (12 bytes,
// where the Sprite is 20, and no floating point left for the band's loop); any other by its
// index in the scene's sprites.
struct Binned {
  std::int16_t ix, iy;
  std::uint16_t code;  // phase + slot * kPhases^2, or kByIndex
  std::uint32_t word;  // RGBA bytes, or the sprite's index
};
static_assert(sizeof(Binned) == 12);
constexpr std::uint16_t kByIndex = 0xffff;

struct SplatBuffers {
  std::vector<Stamps> stamps;               // one per radius of this frame's discs
  std::vector<std::vector<Binned>> binned;  // per thread and band: its discs, in drawing order
};

// 2D discs as point sprites: llvmpipe rasterizes a point as one rectangle, where a quad costs
// two triangle set-ups, which dominate when 2.5e5 discs are a pixel or two wide.
const char* kPointVS = R"(#version 330 core
layout(location = 0) in vec4 inst;
layout(location = 1) in vec4 colour;
uniform vec2 scale;
uniform float ppu;
out float rad_px;
out vec4 col;
void main() {
  rad_px = inst.w * ppu;
  gl_PointSize = 2.0 * (rad_px + 1.0);
  gl_Position = vec4(inst.xy * scale, 0.0, 1.0);
  col = colour;
}
)";
const char* kPointFS = R"(#version 330 core
in float rad_px;
in vec4 col;
out vec4 frag;
void main() {
  vec2 local = (gl_PointCoord * 2.0 - 1.0) * (rad_px + 1.0);
  float a = clamp(rad_px + 0.5 - length(local), 0.0, 1.0);
  if (a <= 0.0) discard;
  frag = vec4(col.rgb, col.a * a);
}
)";

const char* kDiscVS = R"(#version 330 core
layout(location = 0) in vec4 inst;
layout(location = 1) in vec4 colour;
uniform vec2 scale;  // world units -> clip space
uniform float ppu;   // pixels per world unit
out vec2 local;      // pixels from the disc's centre
out float rad_px;
out vec4 col;
void main() {
  vec2 corner = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  rad_px = inst.w * ppu;
  float ext = rad_px + 1.0;  // room for the antialiased rim
  local = corner * ext;
  gl_Position = vec4((inst.xy + corner * (ext / ppu)) * scale, 0.0, 1.0);
  col = colour;
}
)";

// Coverage from the distance to the rim, one pixel wide: antialiasing without multisampling.
const char* kDiscFS = R"(#version 330 core
in vec2 local;
in float rad_px;
in vec4 col;
out vec4 frag;
void main() {
  float a = clamp(rad_px + 0.5 - length(local), 0.0, 1.0);
  if (a <= 0.0) discard;
  frag = vec4(col.rgb, col.a * a);
}
)";

// A billboard facing the eye, large enough to hold the sphere's perspective silhouette; the
// fragment shader ray-casts the sphere and writes its true depth. Both bodies are files under
// assets/shaders that the page of `grainshock view` shares (render/shader_files.h).
std::string sphere_vs() {
  return "#version 330 core\n" + std::string(shader_files::sphere_billboard()) + R"(
layout(location = 0) in vec4 inst;
layout(location = 1) in vec4 colour;
uniform mat4 view;
uniform mat4 proj;
uniform float px_per_depth;  // size of a pixel at unit distance
out vec3 vpos;
flat out vec3 centre;
flat out float radius;
flat out vec4 col;
void main() {
  vec2 corner = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  vec3 c = (view * vec4(inst.xyz, 1.0)).xyz;
  vpos = sphere_billboard(c, inst.w, corner, px_per_depth);
  gl_Position = proj * vec4(vpos, 1.0);
  centre = c;
  radius = inst.w;
  col = colour;
}
)";
}

std::string sphere_fs() {
  return "#version 330 core\n" + std::string(shader_files::sphere_impostor_frag());
}

// The disc fragment shader's coverage rule on the CPU: pixel centres at half-integers, the
// picture's centre at the camera origin, y up. Only the pixels whose centre lies within
// rad + 0.5 of the disc's can be covered, so the loops stop there (a disc half a pixel wide
// touches 2x2 pixels, not the 4x4 of its padded box). Rows [row0, row1) only. The arithmetic is
// that of the first version (double coverage, a blend rounding half up per channel), so the
// pictures stay the same bytes; the four channels of a pixel are blended as one vector (the
// alpha channel, 255 in picture and disc, stays 255.5 -> 255) and a fully covered pixel is
// stored without a blend, since p + 1 * (c - p) + 0.5 truncates to c exactly.
using Lanes = double __attribute__((vector_size(32)));
using IntLanes = std::int32_t __attribute__((vector_size(16)));

void splat_disc(Image& img, const Sprite& d, double ppu, int row0, int row1) {
  const double X = img.width / 2.0 + d.x * ppu, Y = img.height / 2.0 - d.y * ppu;
  const double rad = d.r * ppu;
  const int y0 = std::max(row0, static_cast<int>(std::floor(Y - rad)));
  const int y1 = std::min(row1 - 1, static_cast<int>(std::ceil(Y + rad)) - 1);
  const int x0 = std::max(0, static_cast<int>(std::floor(X - rad)));
  const int x1 = std::min(img.width - 1, static_cast<int>(std::ceil(X + rad)) - 1);
  if (x0 > x1) return;
  const double inner = rad > 0.5 ? (rad - 0.5) * (rad - 0.5) : -1;  // fully covered within
  const double edge = rad + 0.5;
  const std::uint8_t solid[4] = {d.rgba[0], d.rgba[1], d.rgba[2], 255};
  const Lanes colour = {double(d.rgba[0]), double(d.rgba[1]), double(d.rgba[2]), 255.0};
  for (int y = y0; y <= y1; ++y) {
    const double dy = y + 0.5 - Y, dy2 = dy * dy;
    std::uint8_t* p = img.pixel(x0, y);
    for (int x = x0; x <= x1; ++x, p += 4) {
      const double dx = x + 0.5 - X, d2 = dx * dx + dy2;
      if (d2 <= inner) {
        std::memcpy(p, solid, 4);
        continue;
      }
      const double a = std::min(edge - std::sqrt(d2), 1.0);
      if (a <= 0) continue;
      const Lanes was = {double(p[0]), double(p[1]), double(p[2]), double(p[3])};
      const IntLanes out = __builtin_convertvector(was + a * (colour - was) + 0.5, IntLanes);
      for (int k = 0; k < 4; ++k) p[k] = static_cast<std::uint8_t>(out[k]);
    }
  }
}

// Largest pixel radius drawn from stamps (larger discs are few and cover many pixels each) and
// the most radii a frame keeps stamps for (a polydisperse file is drawn disc by disc).
constexpr double kStampMaxPx = 3;
constexpr std::size_t kMaxStampRadii = 4;

void make_stamps(Stamps& st, float r, double ppu) {
  if (st.r == r && st.ppu == ppu) return;  // a movie keeps its stamps from frame to frame
  st.r = r;
  st.ppu = ppu;
  const double rad = r * ppu, edge = rad + 0.5;
  const int reach = static_cast<int>(std::ceil(rad)) + 1;
  st.lo = -reach;
  st.size = 2 * reach + 1;
  const auto cells = static_cast<std::size_t>(st.size) * st.size;
  // Four bytes over the end: a row of four pixels reads its coverage as one word.
  st.alpha.assign(cells * kPhases * kPhases + 4, 0);
  st.box.assign(kPhases * kPhases, {255, 0, 255, 0});
  for (int qy = 0; qy < kPhases; ++qy)
    for (int qx = 0; qx < kPhases; ++qx) {
      const double fx = (qx + 0.5) / kPhases, fy = (qy + 0.5) / kPhases;
      const std::size_t phase = static_cast<std::size_t>(qy) * kPhases + qx;
      std::uint8_t* a = &st.alpha[phase * cells];
      auto& b = st.box[phase];
      for (int j = 0; j < st.size; ++j)
        for (int i = 0; i < st.size; ++i) {
          const double dx = st.lo + i + 0.5 - fx, dy = st.lo + j + 0.5 - fy;
          const double cover = std::min(edge - std::sqrt(dx * dx + dy * dy), 1.0);
          if (cover <= 0) continue;
          const auto a8 = static_cast<std::uint8_t>(std::lround(cover * 255));
          if (a8 == 0) continue;
          a[j * st.size + i] = a8;
          b = {std::min<std::uint8_t>(b[0], i), std::max<std::uint8_t>(b[1], i),
               std::min<std::uint8_t>(b[2], j), std::max<std::uint8_t>(b[3], j)};
        }
    }
}

// A disc from its stamp: the centre's phase picks the coverage, the picture's pixels are
// blended in integers, (p (255 - a) + c a + 127) / 255, which is c where the disc covers fully
// and p where it does not cover at all, so the stamp's box is blended without a branch. The
// channels are blended two at a time in 16-bit lanes of one word (at most 65152 in a lane, so
// no carry crosses), and x / 255 is (x + (x >> 8) + 1) >> 8 for every x up to 65152 (checked
// for all p, c, a). The alpha byte is kept.
void stamp_disc(Image& img, const Binned& d, const Stamps& st, int row0, int row1) {
  const int ix = d.ix, iy = d.iy;
  const std::size_t phase = d.code % (kPhases * kPhases);
  std::uint8_t rgba[4];
  std::memcpy(rgba, &d.word, 4);
  const auto& b = st.box[phase];
  const int x0 = std::max(0, ix + st.lo + b[0]), x1 = std::min(img.width - 1, ix + st.lo + b[1]);
  const int y0 = std::max(row0, iy + st.lo + b[2]), y1 = std::min(row1 - 1, iy + st.lo + b[3]);
  if (x0 > x1) return;
  const std::uint8_t* alpha = &st.alpha[phase * st.size * st.size];
  if (x1 - x0 < 4 && x0 + 4 <= img.width) {
    // Up to four pixels a row (every disc below 1.5 px): the row's four pixels blended at once
    // in 16-bit lanes, by the same formula; coverage 0 beyond the box leaves those as they were.
    // Alpha is blended with 255 here, which keeps the splat's opaque picture opaque.
    using U8x16 = std::uint8_t __attribute__((vector_size(16)));
    using U16x16 = std::uint16_t __attribute__((vector_size(32)));
    const std::uint32_t keep = 0xffffffffu >> (8 * (3 - (x1 - x0)));
    const U16x16 colour = {rgba[0], rgba[1], rgba[2], 255, rgba[0], rgba[1], rgba[2], 255,
                           rgba[0], rgba[1], rgba[2], 255, rgba[0], rgba[1], rgba[2], 255};
    for (int y = y0; y <= y1; ++y) {
      std::uint32_t w4;
      std::memcpy(&w4, alpha + (y - iy - st.lo) * st.size + (x0 - ix - st.lo), 4);
      w4 &= keep;
      U8x16 wb{};
      std::memcpy(&wb, &w4, 4);
      const U16x16 w = __builtin_convertvector(
          __builtin_shufflevector(wb, wb, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3), U16x16);
      std::uint8_t* p = img.pixel(x0, y);
      U8x16 was;
      std::memcpy(&was, p, 16);
      U16x16 x = __builtin_convertvector(was, U16x16) * (255 - w) + colour * w + 127;
      x = (x + (x >> 8) + 1) >> 8;
      const U8x16 out = __builtin_convertvector(x, U8x16);
      std::memcpy(p, &out, 16);
    }
    return;
  }
  constexpr std::uint32_t kLanes = 0x00ff00ffu, kHalf = 0x007f007fu, kOne = 0x00010001u;
  const std::uint32_t c_rb = rgba[0] | std::uint32_t(rgba[2]) << 16, c_ga = rgba[1];
  for (int y = y0; y <= y1; ++y) {
    const std::uint8_t* a = alpha + (y - iy - st.lo) * st.size + (x0 - ix - st.lo);
    std::uint8_t* p = img.pixel(x0, y);
    for (int x = x0; x <= x1; ++x, p += 4) {
      std::uint32_t was;
      std::memcpy(&was, p, 4);
      const std::uint32_t w = *a++, v = 255 - w;
      std::uint32_t rb = (was & kLanes) * v + c_rb * w + kHalf;
      std::uint32_t ga = (was >> 8 & kLanes) * v + c_ga * w + kHalf;
      rb = (rb + (rb >> 8 & kLanes) + kOne) >> 8 & kLanes;
      ga = (ga + (ga >> 8 & kLanes) + kOne) >> 8 & kLanes;
      const std::uint32_t out = rb | (ga << 8 & 0x0000ff00u) | (was & 0xff000000u);
      std::memcpy(p, &out, 4);
    }
  }
}

// Discs in random order write all over a picture larger than the caches, so they are first
// sorted into bands of 32 rows (in drawing order, a disc across two bands into both), and each
// band, filled with the background, is drawn from its own contiguous list with every write close
// by. The threads each sort their consecutive piece of the discs into lists of their own, one
// per band, in one pass (a band is drawn from the first thread's list, then the second's..., so
// in drawing order), and then take bands as they come free:
// the pixels are the same whatever the threads, since bands partition them and each pixel sees
// its discs in drawing order.
void splat_discs(Image& img, const std::uint8_t background[4], const std::vector<Sprite>& discs,
                 double ppu, SplatBuffers& buf) {
  constexpr int kBand = 32;
  const int bands = (img.height + kBand - 1) / kBand;
  const std::size_t n = discs.size();
  const int threads = frame_threads(std::max<std::size_t>(n, img.rgba.size() / 16), 20000);
  // Each thread's list for each band is kept from frame to frame: no page faults for new ones.
  buf.binned.resize(static_cast<std::size_t>(threads) * bands);
  // The radii of each thread's discs in the order met, kMaxStampRadii + 1 at most (then there
  // are too many for stamps); a stamped disc names its radius by its slot here.
  std::vector<std::vector<float>> radii(threads);
  // Stamped discs are binned by pixel and phase, unless the frame turns out to have too many
  // radii for stamps: then it is binned again, every disc by index.
  auto bin = [&](bool stamps) {
    run_on_threads(threads, [&](int t) {
      const auto [first, last] = piece(n, threads, t);
      std::vector<Binned>* lists = &buf.binned[static_cast<std::size_t>(t) * bands];
      for (int b = 0; b < bands; ++b) lists[b].clear();
      std::vector<float>& mine = radii[t];
      mine.clear();
      float last_r = -1;
      std::size_t slot = 0;
      for (std::size_t i = first; i < last; ++i) {
        const Sprite& d = discs[i];
        if (d.r != last_r) {
          last_r = d.r;
          slot = static_cast<std::size_t>(std::find(mine.begin(), mine.end(), d.r) - mine.begin());
          if (slot == mine.size() && mine.size() <= kMaxStampRadii) mine.push_back(d.r);
        }
        const double Y = img.height / 2.0 - d.y * ppu, rad = d.r * ppu;
        const int y0 = std::max(0, static_cast<int>(std::floor(Y - rad)));
        const int y1 = std::min(img.height - 1, static_cast<int>(std::ceil(Y + rad)) - 1);
        if (y0 > y1) continue;  // above or below the picture
        std::int16_t ix = 0, iy = 0;
        std::uint16_t code = kByIndex;
        auto word = static_cast<std::uint32_t>(i);
        if (stamps && slot < kMaxStampRadii && rad <= kStampMaxPx) {
          // As make_stamps reaches and stamp_disc clips: a disc whose stamp lies wholly left or
          // right of the picture draws nothing, and the others' pixels fit 16 bits.
          const double X = img.width / 2.0 + d.x * ppu;
          const double fX = std::floor(X), fY = std::floor(Y);
          const int reach = static_cast<int>(std::ceil(rad)) + 1;
          if (!(fX + reach >= 0 && fX - reach < img.width && fY + reach >= 0 &&
                fY - reach < img.height))
            continue;  // also not a number
          const int qx = std::min(kPhases - 1, static_cast<int>((X - fX) * kPhases));
          const int qy = std::min(kPhases - 1, static_cast<int>((Y - fY) * kPhases));
          ix = static_cast<std::int16_t>(fX);
          iy = static_cast<std::int16_t>(fY);
          code = static_cast<std::uint16_t>((slot * kPhases + qy) * kPhases + qx);
          std::memcpy(&word, d.rgba, 4);
        }
        // Field by field into the list: a record made on the stack and copied whole stalled on
        // forwarding its 16-bit stores to the 64-bit load of the copy.
        for (int b = y0 / kBand; b <= y1 / kBand; ++b) {
          Binned& e = lists[b].emplace_back();
          e.ix = ix;
          e.iy = iy;
          e.code = code;
          e.word = word;
        }
      }
    });
  };
  bin(true);
  std::vector<float> all;
  for (const auto& r : radii)
    for (float x : r)
      if (std::find(all.begin(), all.end(), x) == all.end()) all.push_back(x);
  if (all.size() > kMaxStampRadii) {
    all.clear();
    bin(false);
  }
  std::erase_if(all, [&](float r) { return !(r * ppu <= kStampMaxPx); });
  // Stamps kept for radii still drawn are reused; the others are made anew.
  std::vector<Stamps> kept;
  for (float r : all) {
    auto it = std::find_if(buf.stamps.begin(), buf.stamps.end(),
                           [&](const Stamps& st) { return st.r == r && st.ppu == ppu; });
    kept.push_back(it != buf.stamps.end() ? std::move(*it) : Stamps{});
    make_stamps(kept.back(), r, ppu);
  }
  buf.stamps = std::move(kept);
  // Each thread's slots' stamps (null for a radius drawn without one).
  std::vector<std::array<const Stamps*, kMaxStampRadii>> slots(threads);
  for (int t = 0; t < threads; ++t) {
    slots[t].fill(nullptr);
    for (std::size_t k = 0; k < std::min(radii[t].size(), kMaxStampRadii); ++k)
      for (const Stamps& st : buf.stamps)
        if (st.r == radii[t][k]) slots[t][k] = &st;
  }
  std::atomic<int> next{0};
  std::uint32_t bg;
  std::memcpy(&bg, background, 4);
  run_on_threads(threads, [&](int) {
    for (int b; (b = next.fetch_add(1, std::memory_order_relaxed)) < bands;) {
      const int row0 = b * kBand, row1 = std::min(img.height, row0 + kBand);
      auto* px = reinterpret_cast<std::uint32_t*>(img.pixel(0, row0));
      std::fill(px, px + static_cast<std::size_t>(row1 - row0) * img.width, bg);
      for (int t = 0; t < threads; ++t)
        for (const Binned& d : buf.binned[static_cast<std::size_t>(t) * bands + b]) {
          if (d.code == kByIndex)
            splat_disc(img, discs[d.word], ppu, row0, row1);
          else
            stamp_disc(img, d, *slots[t][d.code / (kPhases * kPhases)], row0, row1);
        }
    }
  });
}

}  // namespace

void check_size(int width, int height, int limit) {
  if (width <= 0 || height <= 0 || width > limit || height > limit)
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is out of range (1 to " + std::to_string(limit) + " pixels a side)");
}

struct Renderer::Impl {
  std::unique_ptr<GLContext> ctx;
  GLApi gl;
  GLuint point_prog = 0, disc_prog = 0, sphere_prog = 0, vao = 0, vbo = 0, ibo = 0;
  std::size_t vbo_bytes = 0, ibo_quads = 0;
  GLuint fbo = 0, colour_rb = 0, depth_rb = 0;  // drawn into (multisampled or not)
  GLuint resolve_fbo = 0, resolve_rb = 0;       // single-sample copy when multisampled
  int fbo_w = 0, fbo_h = 0, fbo_samples = -1;
  int max_size = 0, max_samples = 0;
  float max_point_size = 1;
  std::vector<Sprite> vertices;     // four per particle for quads
  SplatBuffers splat;               // tiny 2D discs by band of rows, for the CPU splats
  SceneScratch scene_scratch;       // the scenes' memory, from frame to frame
  std::vector<std::uint8_t> spare;  // a recycled picture's pixels
  std::vector<std::uint8_t> readback;
  std::optional<OverlayPainter> painter;
  std::string painter_font;
  RenderInfo info;

  OverlayPainter& overlay_painter(const std::string& font) {
    if (!painter || painter_font != font) {
      painter.reset();
      painter.emplace(font);
      painter_font = font;
    }
    return *painter;
  }

  GLuint compile(GLenum type, const char* src) {
    const GLuint s = gl.CreateShader(type);
    gl.ShaderSource(s, 1, &src, nullptr);
    gl.CompileShader(s);
    GLint ok = 0;
    gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[2048] = {};
      gl.GetShaderInfoLog(s, sizeof log, nullptr, log);
      GS_CHECK_MSG(false, std::string("shader does not compile: ") + log);
    }
    return s;
  }
  GLuint link(const char* vs, const char* fs) {
    const GLuint p = gl.CreateProgram();
    const GLuint v = compile(GL_VERTEX_SHADER, vs), f = compile(GL_FRAGMENT_SHADER, fs);
    gl.AttachShader(p, v);
    gl.AttachShader(p, f);
    gl.LinkProgram(p);
    GLint ok = 0;
    gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
      char log[2048] = {};
      gl.GetProgramInfoLog(p, sizeof log, nullptr, log);
      GS_CHECK_MSG(false, std::string("shaders do not link: ") + log);
    }
    gl.DeleteShader(v);
    gl.DeleteShader(f);
    return p;
  }

  void init(Backend backend) {
    ctx = GLContext::create(backend);
    gl.load(*ctx);
    GLint v = 0;
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &v);
    GLint dims[2] = {0, 0};
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    max_size = std::min(
        {kMaxImageSide, static_cast<int>(v), static_cast<int>(dims[0]), static_cast<int>(dims[1])});
    gl.GetIntegerv(GL_MAX_SAMPLES, &v);
    max_samples = v;
    GLfloat range[2] = {1, 1};
    gl.GetFloatv(GL_POINT_SIZE_RANGE, range);
    max_point_size = range[1];
    disc_prog = link(kDiscVS, kDiscFS);
    point_prog = link(kPointVS, kPointFS);
    sphere_prog = link(sphere_vs().c_str(), sphere_fs().c_str());
    gl.GenVertexArrays(1, &vao);
    gl.GenBuffers(1, &vbo);
    gl.GenBuffers(1, &ibo);
    gl.BindVertexArray(vao);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo);
    gl.VertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(Sprite), nullptr);
    gl.VertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(Sprite),
                           reinterpret_cast<const void*>(offsetof(Sprite, rgba)));
    gl.EnableVertexAttribArray(0);
    gl.EnableVertexAttribArray(1);
    GS_CHECK(gl.GetError() == GL_NO_ERROR);
  }

  void free_targets() {
    if (fbo) gl.DeleteFramebuffers(1, &fbo), fbo = 0;
    if (resolve_fbo) gl.DeleteFramebuffers(1, &resolve_fbo), resolve_fbo = 0;
    GLuint rbs[] = {colour_rb, depth_rb, resolve_rb};
    for (GLuint rb : rbs)
      if (rb) gl.DeleteRenderbuffers(1, &rb);
    colour_rb = depth_rb = resolve_rb = 0;
  }

  GLuint renderbuffer(GLenum format, int w, int h, int samples) {
    GLuint rb = 0;
    gl.GenRenderbuffers(1, &rb);
    gl.BindRenderbuffer(GL_RENDERBUFFER, rb);
    if (samples > 0)
      gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, w, h);
    else
      gl.RenderbufferStorage(GL_RENDERBUFFER, format, w, h);
    return rb;
  }

  void ensure_targets(int w, int h, int samples) {
    if (w == fbo_w && h == fbo_h && samples == fbo_samples) return;
    free_targets();
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    colour_rb = renderbuffer(GL_RGBA8, w, h, samples);
    depth_rb = renderbuffer(GL_DEPTH_COMPONENT24, w, h, samples);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_rb);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw UserError("the OpenGL driver cannot make a " + std::to_string(w) + "x" +
                      std::to_string(h) + " framebuffer (out of memory?)");
    if (samples > 0) {
      gl.GenFramebuffers(1, &resolve_fbo);
      gl.BindFramebuffer(GL_FRAMEBUFFER, resolve_fbo);
      resolve_rb = renderbuffer(GL_RGBA8, w, h, 0);
      gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_rb);
      if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw UserError("the OpenGL driver cannot make a resolve framebuffer");
    }
    fbo_w = w, fbo_h = h, fbo_samples = samples;
  }

  void upload(const std::vector<Sprite>& sprites, bool quad_indices) {
    const std::vector<Sprite>* data = &sprites;
    if (quad_indices) {
      vertices.clear();
      vertices.reserve(sprites.size() * 4);
      for (const Sprite& v : sprites) vertices.insert(vertices.end(), 4, v);
      data = &vertices;
    }
    const std::size_t quads = sprites.size();
    if (quad_indices && quads > ibo_quads) {
      // Two triangles per quad; the indices never change, so they grow but are never rewritten.
      ibo_quads = std::max(quads, ibo_quads * 3 / 2);
      std::vector<GLuint> idx(ibo_quads * 6);
      for (std::size_t q = 0; q < ibo_quads; ++q) {
        const auto b = static_cast<GLuint>(4 * q);
        const GLuint tri[6] = {b, b + 1, b + 2, b + 2, b + 1, b + 3};
        std::copy(tri, tri + 6, idx.begin() + static_cast<std::ptrdiff_t>(6 * q));
      }
      gl.BindVertexArray(vao);
      gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(idx.size() * sizeof(GLuint)),
                    idx.data(), GL_STATIC_DRAW);
    }
    const std::size_t bytes = data->size() * sizeof(Sprite);
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo);
    // Orphan and refill: the driver need not wait for the previous frame's draw.
    if (bytes > vbo_bytes) vbo_bytes = std::max(bytes, vbo_bytes * 3 / 2);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vbo_bytes), nullptr, GL_STREAM_DRAW);
    if (bytes) gl.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data->data());
  }
};

Renderer::Renderer(Backend backend) : impl_(std::make_unique<Impl>()) {
  impl_->init(backend);
}

Renderer::~Renderer() {
  if (!impl_ || !impl_->ctx) return;
  auto& gl = impl_->gl;
  impl_->ctx->make_current();
  impl_->free_targets();
  gl.DeleteBuffers(1, &impl_->vbo);
  gl.DeleteBuffers(1, &impl_->ibo);
  gl.DeleteVertexArrays(1, &impl_->vao);
  gl.DeleteProgram(impl_->point_prog);
  gl.DeleteProgram(impl_->disc_prog);
  gl.DeleteProgram(impl_->sphere_prog);
}

const RenderInfo& Renderer::last() const {
  return impl_->info;
}
int Renderer::max_size() const {
  return impl_->max_size;
}
const char* Renderer::backend_name() const {
  return impl_->ctx->backend_name();
}

Scene Renderer::scene(const std::vector<const Snapshot*>& snaps, const Style& style,
                      const View& view) {
  check_size(view.width, view.height, impl_->max_size);
  return build_scene(snaps, style, view, impl_->overlay_painter(style.font), &impl_->scene_scratch);
}

Image Renderer::render(const std::vector<const Snapshot*>& snaps, const Style& style,
                       const View& view) {
  Scene sc = scene(snaps, style, view);
  Image img = draw(sc);
  const Annotations a = annotate(img, sc, impl_->overlay_painter(style.font));
  impl_->info.colorbar = a.colorbar;
  impl_->info.inset = a.inset;
  impl_->info.panels = a.panels;
  impl_->scene_scratch.sprites = std::move(sc.sprites);
  impl_->scene_scratch.shade = std::move(sc.shade);
  return img;
}

void Renderer::recycle(Image&& done) {
  impl_->spare = std::move(done.rgba);
  done = Image{};
}

Image Renderer::draw(const Scene& sc) {
  Impl& m = *impl_;
  GLApi& gl = m.gl;
  const Camera& cam = sc.camera;
  const Style& style = sc.style;
  const Palette& pal = sc.palette;
  const bool three_d = sc.dim == 3;
  check_size(cam.width, cam.height, m.max_size);
  const int width = cam.width, height = cam.height;
  m.info = RenderInfo{};
  m.info.range = sc.range;
  m.info.camera = cam;
  m.info.drawn = sc.sprites.size();
  m.info.v_rms = sc.v_rms;
  float r_min = std::numeric_limits<float>::infinity();
  for (const Sprite& sp : sc.sprites) r_min = std::min(r_min, sp.r);
  if (!sc.sprites.empty()) m.info.disc_radius_px = r_min * cam.magnification();

  // 2D discs below splat_below_px in radius are drawn on the CPU after readback: llvmpipe spends
  // about half a microsecond of CPU per primitive however small, so a paper-size frame (2.5e5
  // discs a pixel wide) costs 150-250 ms through GL and ~15 ms splatted with the same coverage
  // rule. Larger discs go through GL as sprites up to the driver's largest point size, as quads
  // beyond. GL drops a point whose centre is off the viewport, so sprites are drawn into a
  // framebuffer larger by a margin of one sprite radius and the picture read from its middle.
  const double rad_px = sc.r_max * cam.pixels_per_unit();
  const bool splat = !three_d && rad_px < style.splat_below_px;
  const double sprite_px = 2 * (rad_px + 1);
  const int margin = static_cast<int>(std::ceil(sprite_px / 2)) + 1;
  const bool points = !three_d && !splat && sprite_px <= m.max_point_size &&
                      std::max(width, height) + 2 * margin <= m.max_size;
  const int pad = points ? margin : 0;

  // Every pixel is written below, so a recycled picture is not cleared first.
  auto picture = [&] {
    Image img;
    img.width = width;
    img.height = height;
    img.rgba = std::move(m.spare);
    m.spare = {};
    img.rgba.resize(static_cast<std::size_t>(width) * height * 4);
    return img;
  };
  if (splat) {  // nothing for GL to do: the background, then the discs, all on the CPU
    Image img = picture();
    const std::uint8_t bg[4] = {pal.background[0], pal.background[1], pal.background[2], 255};
    splat_discs(img, bg, sc.sprites, cam.pixels_per_unit(), m.splat);
    return img;
  }
  const int samples = three_d ? std::min(std::max(style.msaa, 0), m.max_samples) : 0;
  m.ctx->make_current();
  const int fb_w = width + 2 * pad, fb_h = height + 2 * pad;
  m.ensure_targets(fb_w, fb_h, samples);
  gl.BindFramebuffer(GL_FRAMEBUFFER, m.fbo);
  gl.Viewport(0, 0, fb_w, fb_h);
  gl.ClearColor(pal.background[0] / 255.f, pal.background[1] / 255.f, pal.background[2] / 255.f, 1);
  gl.ClearDepth(1.0);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  m.upload(sc.sprites, !points);
  gl.BindVertexArray(m.vao);
  if (!three_d) {
    gl.Disable(GL_DEPTH_TEST);
    gl.Enable(GL_BLEND);
    gl.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    const GLuint prog = points ? m.point_prog : m.disc_prog;
    gl.Enable(GL_PROGRAM_POINT_SIZE);
    gl.UseProgram(prog);
    gl.Uniform1f(gl.GetUniformLocation(prog, "ppu"), static_cast<float>(cam.pixels_per_unit()));
    const GLint loc = gl.GetUniformLocation(prog, "scale");
    const double pad_units = pad / cam.pixels_per_unit();
    gl.Uniform2f(loc, static_cast<float>(1 / (cam.half_w + pad_units)),
                 static_cast<float>(1 / (cam.half_h + pad_units)));
  } else {
    gl.Disable(GL_BLEND);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.DepthMask(GL_TRUE);
    if (samples > 0)
      gl.Enable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    else
      gl.Disable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    gl.UseProgram(m.sphere_prog);
    const Eigen::Matrix4f view_f = cam.view.cast<float>(), proj_f = cam.proj.cast<float>();
    gl.UniformMatrix4fv(gl.GetUniformLocation(m.sphere_prog, "view"), 1, GL_FALSE, view_f.data());
    gl.UniformMatrix4fv(gl.GetUniformLocation(m.sphere_prog, "proj"), 1, GL_FALSE, proj_f.data());
    gl.Uniform1f(gl.GetUniformLocation(m.sphere_prog, "px_per_depth"),
                 static_cast<float>(2 * cam.tan_half_y / height));
    const Eigen::Vector3f light = Eigen::Vector3f(-0.4f, 0.55f, 0.75f).normalized();
    gl.Uniform3f(gl.GetUniformLocation(m.sphere_prog, "light"), light.x(), light.y(), light.z());
  }
  if (sc.sprites.empty()) {
  } else if (points)
    gl.DrawArrays(GL_POINTS, 0, static_cast<GLsizei>(sc.sprites.size()));
  else
    gl.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(sc.sprites.size() * 6), GL_UNSIGNED_INT,
                    nullptr);
  if (samples > 0) {
    gl.Disable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, m.fbo);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, m.resolve_fbo);
    gl.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, m.resolve_fbo);
  }
  Image img = picture();
  m.readback.resize(img.rgba.size());
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(pad, pad, width, height, GL_RGBA, GL_UNSIGNED_BYTE, m.readback.data());
  if (const GLenum e = gl.GetError(); e != GL_NO_ERROR)
    throw UserError("OpenGL error " + std::to_string(e) + " while rendering " +
                    std::to_string(width) + "x" + std::to_string(height));
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  for (int y = 0; y < height; ++y)  // GL's rows run bottom-up
    std::memcpy(img.pixel(0, y), m.readback.data() + (height - 1 - y) * row, row);
  return img;
}

}  // namespace gs::render
