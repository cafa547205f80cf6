#include "render/page_frame.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "render/overlay.h"
#include "render/scene.h"
#include "sim/error.h"

namespace gs::render {
namespace {

template <class T>
void append(std::string& out, const T* data, std::size_t n) {
  out.append(reinterpret_cast<const char*>(data), n * sizeof(T));
  out.resize((out.size() + 3) / 4 * 4, '\0');  // the next section starts 4-byte aligned
}

// IEEE 754 binary16, rounded to nearest (ties away from zero: hover values need 3 digits, not
// the last bit): the hover columns take half the bytes of float32.
std::uint16_t half(float v) {
  std::uint32_t x;
  std::memcpy(&x, &v, 4);
  const std::uint16_t sign = (x >> 16) & 0x8000;
  const std::uint32_t abs = x & 0x7fffffff;
  if (abs > 0x7f800000) return sign | 0x7e00;   // NaN
  if (abs >= 0x477ff000) return sign | 0x7c00;  // beyond 65504: infinity
  if (abs < 0x33000000) return sign;            // below half the least
  const int e = static_cast<int>(abs >> 23) - 127;
  if (e < -14) {  // subnormal
    const std::uint32_t m = (abs & 0x7fffff) | 0x800000;
    const int shift = -e - 14 + 13;
    return sign | static_cast<std::uint16_t>((m + (1u << (shift - 1))) >> shift);
  }
  const std::uint32_t r = abs + 0x1000;  // round the 13 dropped bits
  return sign | static_cast<std::uint16_t>(((r >> 23) - 112) << 10 | ((r >> 13) & 0x3ff));
}

// The file's index of each sprite, in the scene's drawing order: build_scene draws the inactive
// particles it shows first, then the active ones (or, before any collision, the moving ones),
// each layer in the file's order, those the camera cannot see left out.
std::vector<std::uint32_t> sprite_indices(const Snapshot& s, const Style& style,
                                          const Camera& cam) {
  const bool any = std::find(s.active.begin(), s.active.end(), 1) != s.active.end();
  const bool moving = !any && s.has_velocity();
  std::vector<std::uint32_t> idx;
  auto pass = [&](auto&& take) {
    for (std::size_t i = 0; i < s.size(); ++i)
      if (take(i) && cam.visible(s.position[i], s.radius[i]))
        idx.push_back(static_cast<std::uint32_t>(i));
  };
  if (style.show_inactive) pass([&](std::size_t i) { return !s.active[i]; });
  pass([&](std::size_t i) { return s.active[i] || (moving && s.velocity[i].squaredNorm() > 0); });
  return idx;
}

// What render frames: the active particles' centres, or all of them when none is active.
void frame_fit(const Snapshot& s, const Eigen::Vector3d& origin, PageFrame& f) {
  const bool any = std::find(s.active.begin(), s.active.end(), 1) != s.active.end();
  Eigen::AlignedBox3d box;
  double r2 = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (!any || s.active[i]) {
      box.extend(s.position[i] - origin);
      r2 = std::max(r2, (s.position[i] - origin).squaredNorm());
    }
  if (box.isEmpty()) box.extend(Eigen::Vector3d::Zero());
  for (int k = 0; k < 3; ++k) f.fit_lo[k] = box.min()[k], f.fit_hi[k] = box.max()[k];
  for (double r : s.radius) f.r_max = std::max(f.r_max, r);
  f.sphere = std::sqrt(r2) + f.r_max;
}

void pack_positions(const Scene& sc, PageFrame& f) {
  const int dim = f.dim;
  for (int k = 0; k < dim; ++k) f.lo[k] = INFINITY, f.hi[k] = -INFINITY;
  for (const Sprite& p : sc.sprites) {
    const float c[3] = {p.x, p.y, p.z};
    for (int k = 0; k < dim; ++k)
      f.lo[k] = std::min(f.lo[k], double(c[k])), f.hi[k] = std::max(f.hi[k], double(c[k]));
  }
  double worst = 0;
  for (int k = 0; k < dim; ++k) {
    if (sc.sprites.empty()) f.lo[k] = f.hi[k] = 0;
    worst = std::max(worst, (f.hi[k] - f.lo[k]) / 2 / 65535);
  }
  f.error_diameters = f.r_max > 0 ? worst / (2 * f.r_max) : 0;
  std::vector<std::uint16_t> q(sc.sprites.size() * dim);
  for (std::size_t i = 0; i < sc.sprites.size(); ++i) {
    const float c[3] = {sc.sprites[i].x, sc.sprites[i].y, sc.sprites[i].z};
    for (int k = 0; k < dim; ++k) {
      const double span = f.hi[k] - f.lo[k];
      const double u = span > 0 ? (c[k] - f.lo[k]) / span : 0;
      q[i * dim + k] = static_cast<std::uint16_t>(std::lround(std::clamp(u, 0.0, 1.0) * 65535));
    }
  }
  append(f.bytes, q.data(), q.size());
}

void pack_values(const Snapshot& s, const Scene& sc, const std::vector<std::uint32_t>& idx,
                 PageFrame& f) {
  std::vector<std::uint8_t> colour(sc.shade.size());
  for (std::size_t i = 0; i < colour.size(); ++i)
    colour[i] =
        std::isnan(sc.shade[i])
            ? 255
            : static_cast<std::uint8_t>(std::lround(std::clamp(sc.shade[i], 0.0f, 1.0f) * 254));
  append(f.bytes, colour.data(), colour.size());
  append(f.bytes, idx.data(), idx.size());
  f.uniform_radius =
      std::all_of(idx.begin(), idx.end(), [&](std::uint32_t i) { return s.radius[i] == f.r_max; });
  if (!f.uniform_radius) {
    std::vector<std::uint16_t> r(idx.size());
    for (std::size_t i = 0; i < idx.size(); ++i)
      r[i] = static_cast<std::uint16_t>(std::lround(s.radius[idx[i]] / f.r_max * 65535));
    append(f.bytes, r.data(), r.size());
  }
  std::vector<std::uint16_t> v(idx.size());
  std::vector<float> exact(idx.size());
  // Whole numbers (ids, types, counts) are kept exactly as float32, the rest as half floats.
  auto column = [&](const std::string& name, auto&& value) {
    f.columns.push_back(name);
    bool whole = true;
    for (std::size_t i = 0; i < idx.size(); ++i) {
      const double x = value(idx[i]);
      whole = whole && x == std::floor(x) && std::abs(x) < 0x1p24;
      exact[i] = static_cast<float>(x);
      v[i] = half(exact[i]);
    }
    f.column_exact.push_back(whole);
    if (whole)
      append(f.bytes, exact.data(), exact.size());
    else
      append(f.bytes, v.data(), v.size());
  };
  if (!s.velocity.empty()) column("speed", [&](std::size_t i) { return s.velocity[i].norm(); });
  if (!s.first_collision.empty())
    column("first_collision", [&](std::size_t i) { return s.first_collision[i]; });
  for (const Column& c : s.columns) column(c.name, [&](std::size_t i) { return c.values[i]; });
}

}  // namespace

std::vector<std::uint8_t> page_lut(const Style& style) {
  const Colormap cmap = picture_colormap(style);
  std::vector<std::uint8_t> lut;
  for (int k = 0; k < 255; ++k) {
    const Rgb8 c = cmap.at8(k / 254.0);
    lut.insert(lut.end(), c.begin(), c.end());
  }
  const Rgb8 grey = palette(style.background).inactive;
  lut.insert(lut.end(), grey.begin(), grey.end());
  return lut;
}

PageFrame make_page_frame(const Snapshot& s, const Style& style) {
  Style st = style;
  st.colorbar = st.inset = st.occlusion_cull = false;
  st.legend = false;
  View view;  // fitted, all the particles: the page cuts its own slab
  OverlayPainter painter(st.font);
  const Scene sc = build_scene({&s}, st, view, painter);
  PageFrame f;
  f.dim = s.info.dim;
  f.count = sc.sprites.size();
  f.label = sc.time_text;
  f.has_time = s.info.has_time;
  f.t = s.info.time;
  if (s.info.density) {
    f.has_t_paper = true;
    f.t_paper = s.info.time * s.info.speed.value_or(1.0) * std::pow(*s.info.density, 1.0 / f.dim);
  }
  f.step = s.info.step.value_or(-1);
  for (int k = 0; k < 3; ++k) f.origin[k] = sc.camera.origin[k];
  f.range = sc.range;
  f.bar_label = sc.bar_label;
  f.bar_note = sc.bar_note;
  f.colorbar = style.field != Field::None;
  frame_fit(s, sc.camera.origin, f);
  const std::vector<std::uint32_t> idx = sprite_indices(s, st, sc.camera);
  GS_CHECK(idx.size() == sc.sprites.size());
  pack_positions(sc, f);
  pack_values(s, sc, idx, f);
  return f;
}

}  // namespace gs::render
