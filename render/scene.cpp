#include "render/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "render/field.h"
#include "render/frame_threads.h"
#include "render/occlusion.h"
#include "render/overlay.h"
#include "sim/error.h"

namespace gs::render {
namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string time_text(const SnapshotInfo& in) {
  // A file without a time is labelled by its step (LAMMPS, HOOMD), not by a time of 0.
  if (!in.has_time) return in.step ? "step " + std::to_string(*in.step) : std::string();
  std::string t = "t = " + fmt("%.6g", in.time);
  if (in.density)
    t += "   t_paper = " +
         fmt("%.6g", in.time * in.speed.value_or(1.0) * std::pow(*in.density, 1.0 / in.dim));
  return t;
}

bool any_active(const Snapshot& s) {
  return std::find(s.active.begin(), s.active.end(), 1) != s.active.end();
}

// Sorts the spheres nearest first (bucket sort on the nearest depth) and keeps those the
// occlusion buffer cannot prove hidden.
void cull_occluded(Scene& sc) {
  const Camera& cam = sc.camera;
  const std::size_t n = sc.sprites.size();
  if (n == 0) return;
  const double fy = cam.height / (2 * cam.tan_half_y), fx = cam.width / (2 * cam.tan_half_x);
  constexpr std::uint32_t kBuckets = 4096;
  const double scale = kBuckets / (cam.far - cam.near);
  std::vector<std::uint32_t> bucket_of(n), bucket_start(kBuckets + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Sprite& v = sc.sprites[i];
    const double depth =
        -(cam.view.row(2).head<3>().dot(Eigen::Vector3d(v.x, v.y, v.z)) + cam.view(2, 3));
    const double b = std::clamp((depth - v.r - cam.near) * scale, 0.0, kBuckets - 1.0);
    bucket_of[i] = static_cast<std::uint32_t>(b);
    ++bucket_start[bucket_of[i] + 1];
  }
  for (std::uint32_t b = 0; b < kBuckets; ++b) bucket_start[b + 1] += bucket_start[b];
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[bucket_start[bucket_of[i]]++] = static_cast<std::uint32_t>(i);
  OcclusionBuffer occlusion;
  occlusion.reset(cam.width, cam.height);
  std::vector<Sprite> kept;
  std::vector<float> kept_shade;
  for (std::uint32_t i : order) {
    const Sprite& v = sc.sprites[i];
    const Eigen::Vector4d e = cam.view * Eigen::Vector4d(v.x, v.y, v.z, 1);
    if (occlusion.test_and_insert(
            sphere_footprint(e.head<3>(), v.r, fx, fy, cam.width, cam.height))) {
      kept.push_back(v);
      kept_shade.push_back(sc.shade[i]);
    }
  }
  sc.sprites = std::move(kept);
  sc.shade = std::move(kept_shade);
}

}  // namespace

Palette palette(Background b) {
  if (b == Background::Dark) return {{14, 14, 18}, {235, 235, 235}, {72, 72, 78}};
  return {{255, 255, 255}, {20, 20, 20}, {206, 206, 206}};
}

Colormap picture_colormap(const Style& style) {
  return Colormap::by_name(style.colormap).against(palette(style.background).background);
}

Rgb8 overlay_colour(std::size_t index) {
  static const Rgb8 k[] = {{0, 114, 178}, {230, 159, 0},  {0, 158, 115}, {204, 121, 167},
                           {213, 94, 0},  {86, 180, 233}, {240, 228, 66}};
  return k[index % std::size(k)];
}

// The style's settings are the flags of render and movie (Python's keywords): a value outside what
// one accepts, or two that exclude each other, is a usage error naming the flags.
void check_style(const Style& style) {
  Colormap::by_name(style.colormap);
  if (style.range) {
    const auto [lo, hi] = *style.range;
    if (!std::isfinite(lo) || !std::isfinite(hi) || lo >= hi)
      throw UsageError("--range " + fmt("%g", lo) + " " + fmt("%g", hi) +
                       ": MIN must be below MAX");
    if (style.scale == Scale::Log && lo <= 0)
      throw UsageError("--range with --scale log needs MIN > 0 (got " + fmt("%g", lo) + ")");
  }
  if (style.scale == Scale::Log &&
      (style.field == Field::RadialVelocity || style.field == Field::ScaledRadialVelocity))
    throw UsageError("--scale log: radial velocity takes both signs; it cannot be coloured on a "
                     "log scale");
  if (!(style.percentile_low >= 0 && style.percentile_low < style.percentile_high &&
        style.percentile_high <= 100))
    throw UsageError("--percentiles " + fmt("%g", style.percentile_low) + " " +
                     fmt("%g", style.percentile_high) + ": must satisfy 0 <= LOW < HIGH <= 100");
  // 64 is above every GL driver's largest sample count (the renderer takes the driver's largest
  // below it): a larger or negative number is a typing error, not a wish for more quality.
  if (style.msaa < 0 || style.msaa > kMaxMsaa)
    throw UsageError("--msaa " + std::to_string(style.msaa) + ": must be in [0, " +
                     std::to_string(kMaxMsaa) + "] samples per pixel");
}

namespace {

// Colouring of a scene but its sprites: the field's values (a single snapshot; an overlay is
// coloured by time), their range, the colour bar's words, the time label and the legend.
void colour_scale(Scene& sc, const std::vector<const Snapshot*>& snaps, std::vector<double>& values) {
  const Style& style = sc.style;
  values.clear();
  if (!sc.overlay) {
    const Snapshot& s = *snaps.front();
    field_values(s, style.field, &sc.v_rms, style.column, values);
    const std::vector<std::uint8_t> all(any_active(s) ? 0 : s.size(), 1);
    const auto& mask = any_active(s) ? s.active : all;
    const auto fixed = style.range_per_frame ? std::nullopt : default_range(style.field, sc.dim);
    sc.range = style.range ? *style.range
               : fixed     ? *fixed
                           : auto_range(values, mask, style.scale, style.percentile_low,
                                        style.percentile_high);
    if (is_scaled(style.field) && sc.v_rms > 0) sc.bar_note = "v_rms = " + fmt("%.3g", sc.v_rms);
    if (style.inset) sc.inset.emplace();  // its profile is taken in the sprite pass
  }
  sc.bar_label = !style.bar_label.empty()       ? style.bar_label
                 : style.field == Field::Column ? style.column
                                                : field_label(style.field);
  if (style.field == Field::None) sc.style.colorbar = false;  // one colour says nothing
  if (style.scale == Scale::Log) sc.bar_label += " (log)";
  sc.time_text = time_text(snaps.front()->info);
  for (std::size_t k = 0; sc.overlay && k < snaps.size(); ++k)
    sc.legend.emplace_back(overlay_colour(k), time_text(snaps[k]->info));
  // Types are categories: a palette and a legend of their names say more than a colour bar.
  if (!sc.overlay && style.field == Field::Type) {
    sc.style.colorbar = false;
    const auto& names = snaps.front()->type_names;
    for (std::size_t k = 0; k < names.size(); ++k) sc.legend.emplace_back(overlay_colour(k), names[k]);
  }
}

// Pixels a framed scene leaves to its overlays: the colour bar or legend on the right, a 2D
// legend above instead when that leaves more room (square or tall pictures, a legend too wide to
// sit beside it), the inset on the left. An explicitly centred view keeps none (but a shot).
struct Reserve {
  int right = 0, top = 0, left = 0, bottom = 0;
  bool shot = false;  // a 2D following camera's shot (View::half_width)
  int narrow_by() const { return right + left; }
  int shift_px() const { return right - left; }
  int lower_by() const { return top + bottom; }
  int raise_px() const { return top - bottom; }
};

Reserve overlay_reserve(const Scene& sc, const View& view, OverlayPainter& painter) {
  const Style& style = sc.style;
  const bool three_d = sc.dim == 3;
  Reserve r;
  r.shot = !three_d && view.centre && view.half_width > 0;
  if (view.centre && !r.shot) return r;
  if (sc.inset) r.left = painter.inset_width(view.width, view.height);
  if (sc.style.colorbar && !sc.overlay)
    r.right = painter.colorbar_width(view.width, view.height, sc.range, style.scale, sc.bar_label,
                                     sc.bar_note);
  else if (style.legend && !sc.legend.empty())
    r.right = painter.legend_width(view.width, view.height, sc.legend);
  if (style.legend && !sc.legend.empty() && !three_d) {
    const int top = painter.legend_height(view.width, view.height, sc.legend.size());
    if (top < view.height / 2 &&
        std::min(view.width, view.height - top) > std::min(view.width - r.right, view.height)) {
      r.right = 0;
      r.top = top;
    }
  }
  if (r.right + r.left >= view.width / 2) r.right = r.left = 0;
  return r;
}

// Positions folded into the box of the first snapshot that has one (rectangular: each axis its
// own edge) when the view frames the box; unchanged otherwise.
class BoxWrap {
 public:
  BoxWrap(const std::vector<const Snapshot*>& snaps, Framing framing, int dim) : dim_(dim) {
    for (const Snapshot* s : snaps)
      if (!boxed_ && s->info.has_box()) boxed_ = &s->info;
    on_ = framing == Framing::Box && boxed_;
    if (boxed_ && boxed_->box.allFinite()) inside_ = boxed_->box * (1 - 0x1p-50);
  }
  bool on() const { return on_; }
  const SnapshotInfo& box() const { return *boxed_; }
  Eigen::Vector3d operator()(const Eigen::Vector3d& p) const {
    if (!on_) return p;
    return {axis(p.x(), 0), dim_ > 1 ? axis(p.y(), 1) : p.y(), dim_ > 2 ? axis(p.z(), 2) : p.z()};
  }

 private:
  // Below `inside_` (a hair under the edge) x / edge rounds below 1, its floor is 0 and the
  // wrap leaves origin + x: the division, the slowest step of a frame's scene, is skipped for
  // the particles already in the box, with the same bits. Axis by axis in registers: a loop over
  // the axes of a copy in memory, read back whole, stalled every particle on the stores it had
  // not yet forwarded (a third of the scene's time).
  double axis(double p, int k) const {
    const double x = p - boxed_->origin[k], edge = boxed_->box[k];
    return x >= 0 && x <= inside_[k] ? boxed_->origin[k] + x
                                     : boxed_->origin[k] + x - edge * std::floor(x / edge);
  }
  const SnapshotInfo* boxed_ = nullptr;
  bool on_ = false;
  int dim_;
  Eigen::Vector3d inside_ = Eigen::Vector3d::Constant(-1);
};

// What to frame: the box when wrapping, else the active particles of all snapshots, else all.
Eigen::AlignedBox3d framed_region(const std::vector<const Snapshot*>& snaps, const BoxWrap& wrap) {
  Eigen::AlignedBox3d fit;
  if (wrap.on()) {
    fit.extend(wrap.box().origin);
    fit.extend(wrap.box().origin + wrap.box().box);
  }
  for (int pass = 0; pass < 2 && fit.isEmpty(); ++pass)
    for (const Snapshot* s : snaps)
      for (std::size_t i = 0; i < s->size(); ++i)
        if (pass == 1 || s->active[i]) fit.extend(wrap(s->position[i]));
  return fit;
}

// A sphere fitted into the part of the picture the overlays leave, its centre in the middle of it.
Camera frame_sphere_3d(const Eigen::Vector3d& c, double radius, const View& view,
                       const Reserve& reserve) {
  if (reserve.narrow_by() <= 0 && reserve.lower_by() <= 0) return make_camera_3d(c, radius, view);
  View narrow = view;
  narrow.width -= reserve.narrow_by();
  if (reserve.lower_by() > 0) {  // the field of view is vertical: narrowed with the height
    constexpr double deg = std::numbers::pi / 180;
    narrow.height -= reserve.lower_by();
    narrow.fov = 2 / deg *
                 std::atan(std::tan(view.fov * deg / 2) * narrow.height / double(view.height));
  }
  const Camera fitted = make_camera_3d(c, radius, narrow);
  View shifted = view;
  shifted.distance = fitted.distance;
  const double ppu = narrow.height / (2 * fitted.distance * fitted.tan_half_y);
  Eigen::Vector3d centre =
      c + fitted.view.block<1, 3>(0, 0).transpose() * (reserve.shift_px() / 2.0 / ppu);
  if (reserve.raise_px() != 0)  // the camera's up is row 1 of its view
    centre += fitted.view.block<1, 3>(1, 0).transpose() * (reserve.raise_px() / 2.0 / ppu);
  shifted.centre = centre;
  return make_camera_3d(c, radius, shifted);
}

// What a camera must show: 2D the framed region, 3D a bounding sphere about the region's centre
// (tighter than the box's corners for a shell).
struct Subject {
  int dim = 2;
  Eigen::AlignedBox3d fit;
  double r_max = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
};

Subject subject(const std::vector<const Snapshot*>& snaps, const Eigen::AlignedBox3d& fit,
                bool wrap, int dim, double r_max) {
  Subject sub{dim, fit, r_max};
  if (dim != 3) return sub;
  const Eigen::Vector3d c = fit.isEmpty() ? Eigen::Vector3d::Zero() : fit.center().eval();
  double r2 = 0;
  const bool all =
      std::none_of(snaps.begin(), snaps.end(), [](const Snapshot* s) { return any_active(*s); });
  if (wrap)
    r2 = (fit.sizes() / 2).squaredNorm();
  else
    for (const Snapshot* s : snaps)
      for (std::size_t i = 0; i < s->size(); ++i)
        if (all || s->active[i]) r2 = std::max(r2, (s->position[i] - c).squaredNorm());
  sub.centre = c;
  sub.radius = std::sqrt(r2) + r_max;
  return sub;
}

// 2D: fitted into the part of the picture the overlays leave free, then widened to the whole.
Camera frame_2d(const Eigen::AlignedBox3d& fit, double r_max, const View& view,
                const Reserve& reserve) {
  View open_area = view;
  open_area.width -= reserve.narrow_by();
  open_area.height -= reserve.lower_by();
  Camera cam = make_camera_2d(fit, r_max, open_area);
  if (reserve.shot) {
    const double half_h = view.half_width * view.height / view.width;
    const double ppu_shot =
        std::min(open_area.width / (2 * view.half_width), open_area.height / (2 * half_h));
    cam.half_w = open_area.width / (2 * ppu_shot);
    cam.half_h = open_area.height / (2 * ppu_shot);
  }
  const double ppu = cam.pixels_per_unit();
  if (reserve.narrow_by() > 0) {
    cam.width = view.width;
    cam.half_w = view.width / (2 * ppu);
    cam.origin.x() += reserve.shift_px() / (2 * ppu);
  }
  if (reserve.lower_by() > 0) {
    cam.height = view.height;
    cam.half_h = view.height / (2 * ppu);
    cam.origin.y() += reserve.raise_px() / (2 * ppu);  // world y points up the picture
  }
  return cam;
}

Camera frame(const Subject& sub, const View& view, const Reserve& reserve) {
  return sub.dim == 3 ? frame_sphere_3d(sub.centre, sub.radius, view, reserve)
                      : frame_2d(sub.fit, sub.r_max, view, reserve);
}

// Where the subject lies in the picture (pixels, y down), clipped to it. 2D: the region with the
// particles' radius (a shot: its box); 3D: the box of the bounding sphere's outline, widened by
// a twentieth for the stretch of a sphere seen off the axis.
Rect content_rect(const Subject& sub, const Camera& cam, const View& view, bool shot) {
  double x0, x1, y0, y1;
  if (sub.dim == 3) {
    const Eigen::Vector4d e = cam.view * (sub.centre - cam.origin).homogeneous();
    const double d = e.head<3>().norm(), depth = -e.z();
    if (!(depth > sub.radius && d > sub.radius)) return {0, 0, cam.width, cam.height};
    const double fx = cam.width / (2 * cam.tan_half_x), fy = cam.height / (2 * cam.tan_half_y);
    const double cx = cam.width / 2.0 + fx * e.x() / depth, cy = cam.height / 2.0 - fy * e.y() / depth;
    const double r = 1.05 * std::max(fx, fy) * sub.radius / std::sqrt(d * d - sub.radius * sub.radius) + 1;
    x0 = cx - r, x1 = cx + r, y0 = cy - r, y1 = cy + r;
  } else {
    Eigen::AlignedBox3d box = sub.fit;
    if (shot) {
      const Eigen::Vector3d half(view.half_width, view.half_width * view.height / view.width, 0);
      box = Eigen::AlignedBox3d(*view.centre - half, *view.centre + half);
    } else {
      box.min().array() -= sub.r_max;
      box.max().array() += sub.r_max;
    }
    const double ppu = cam.pixels_per_unit();
    x0 = cam.width / 2.0 + (box.min().x() - cam.origin.x()) * ppu;
    x1 = cam.width / 2.0 + (box.max().x() - cam.origin.x()) * ppu;
    y0 = cam.height / 2.0 - (box.max().y() - cam.origin.y()) * ppu;
    y1 = cam.height / 2.0 - (box.min().y() - cam.origin.y()) * ppu;
  }
  auto clip = [](double v, int hi) { return static_cast<int>(std::clamp(v, 0.0, double(hi))); };
  return {clip(std::floor(x0), cam.width), clip(std::floor(y0), cam.height),
          clip(std::ceil(x1), cam.width), clip(std::ceil(y1), cam.height)};
}

bool overlaps(const Rect& a, const Rect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}
bool overlaps(const Rect& a, const std::vector<Rect>& panels) {
  return std::any_of(panels.begin(), panels.end(), [&](const Rect& p) { return overlaps(a, p); });
}

// The panels the overlays will take, as annotate() paints them: the colour bar's strip of the
// right edge or the legend, the inset and, in a still, the time label (a movie's shot leaves it
// out: its width changes with the digits, and the shot's framing must not).
std::vector<Rect> overlay_panels(const Scene& sc, const View& view, bool shot,
                                 OverlayPainter& painter) {
  const int w = view.width, h = view.height;
  std::vector<Rect> out;
  if (sc.style.legend && !sc.legend.empty())
    out.push_back({w - painter.legend_width(w, h, sc.legend), 0, w,
                   painter.legend_height(w, h, sc.legend.size())});
  if (sc.overlay) return out;
  if (sc.style.colorbar)
    out.push_back({w - painter.colorbar_width(w, h, sc.range, sc.style.scale, sc.bar_label,
                                              sc.bar_note),
                   0, w, h});
  if (sc.style.time_label && !sc.time_text.empty() && !shot)
    out.push_back(painter.top_left_label_panel(w, h, sc.time_text));
  if (sc.inset) out.push_back(painter.inset_panel(w, h));
  return out;
}

// The camera of the reserve the overlays ask for, if the subject then keeps clear of their
// panels; else the most magnified of the rectangles between the panels' edges that keeps it
// clear (at 4:3 the inset and colour bar together take more than half the width: the subject
// goes above the inset instead).
// The scale bar's panel (bottom left, above the inset) depends on the camera's magnification.
struct Panels {
  std::vector<Rect> fixed;
  bool scale_bar = false;
  int below_top = -1;
  OverlayPainter* painter = nullptr;
  bool clear(const Rect& content, const Camera& cam) const {
    if (overlaps(content, fixed)) return false;
    return !scale_bar || !overlaps(content, painter->scale_bar_panel(cam.width, cam.height,
                                                                     cam.pixels_per_unit(),
                                                                     below_top));
  }
};

Camera frame_clear_of(const Subject& sub, const View& view, const Reserve& asked,
                      Panels panels_of) {
  Camera cam = frame(sub, view, asked);
  if (panels_of.fixed.empty() && !panels_of.scale_bar) return cam;
  if (panels_of.clear(content_rect(sub, cam, view, asked.shot), cam)) return cam;
  std::vector<Rect> panels = panels_of.fixed;
  if (panels_of.scale_bar)
    panels.push_back(panels_of.painter->scale_bar_panel(view.width, view.height,
                                                        cam.pixels_per_unit(), panels_of.below_top));
  std::vector<int> xs{0, view.width}, ys{0, view.height};
  for (const Rect& p : panels) {
    xs.insert(xs.end(), {std::clamp(p.x0, 0, view.width), std::clamp(p.x1, 0, view.width)});
    ys.insert(ys.end(), {std::clamp(p.y0, 0, view.height), std::clamp(p.y1, 0, view.height)});
  }
  std::sort(xs.begin(), xs.end());
  std::sort(ys.begin(), ys.end());
  double best = -1;
  for (std::size_t a = 0; a < xs.size(); ++a)
    for (std::size_t b = a + 1; b < xs.size(); ++b)
      for (std::size_t c = 0; c < ys.size(); ++c)
        for (std::size_t d = c + 1; d < ys.size(); ++d) {
          const Rect open{xs[a], ys[c], xs[b], ys[d]};
          if (open.x1 - open.x0 < view.width / 4 || open.y1 - open.y0 < view.height / 4 ||
              overlaps(open, panels))
            continue;
          const Reserve r{view.width - open.x1, open.y0, open.x0, view.height - open.y1, asked.shot};
          const Camera tried = frame(sub, view, r);
          const double m = tried.magnification();  // the larger, the better framed
          if (m > best && panels_of.clear(content_rect(sub, tried, view, asked.shot), tried))
            best = m, cam = tried;
        }
  return cam;
}

// The sprites of a framed scene: culled to the camera, coloured, in drawing order, and the
// inset's copy of the active particles.
class SpritePass {
 public:
  SpritePass(Scene& sc, SceneScratch& keep, const BoxWrap& wrap, const Snapshot& first)
      : sc_(sc),
        keep_(keep),
        wrap_(wrap),
        cmap_(picture_colormap(sc.style)),
        profile_(sc.inset && first.has_velocity()),
        speed_values_(sc.style.field == Field::Speed || sc.style.field == Field::ScaledSpeed),
        by_type_(!sc.overlay && sc.style.field == Field::Type),
        scaled_inset_(is_scaled(sc.style.field) && sc.v_rms > 0) {}
  void run(const std::vector<const Snapshot*>& snaps);

 private:
  // Where a pass puts sprites (and the inset's copy of the active particles): room for every
  // particle of its piece, written through a pointer and counted. push_back kept the vector's
  // end in memory, reloaded after every sprite since the colour bytes may alias it.
  struct Out {
    Sprite* sprites;
    float* shade;
    std::size_t& count;
    std::vector<Eigen::Vector3d>& band_x;
    std::vector<double>& band_v;
  };
  void push(Out& out, const Eigen::Vector3d& p, double r, Rgb8 c, float shade) const {
    const Camera& cam = sc_.camera;
    if (!cam.visible(p, r)) return;
    const Eigen::Vector3d d = p - cam.origin;
    out.sprites[out.count] = {static_cast<float>(d.x()),
                              static_cast<float>(d.y()),
                              static_cast<float>(sc_.dim == 3 ? d.z() : 0.0),
                              static_cast<float>(r),
                              {c[0], c[1], c[2], 255}};
    out.shade[out.count++] = shade;
  }
  void inactive(const Snapshot& s, Out& out, std::size_t i) const {
    push(out, wrap_(s.position[i]), s.radius[i], sc_.palette.inactive, std::nanf(""));
  }
  void active(const Snapshot& s, bool moving, Rgb8 time_colour, Out& out, std::size_t i) const;
  template <class Visit>
  void in_order(std::size_t n, Visit&& visit);

  Scene& sc_;
  SceneScratch& keep_;
  const BoxWrap& wrap_;
  const Colormap cmap_;
  const bool profile_, speed_values_, by_type_, scaled_inset_;
  std::vector<Eigen::Vector3d> band_x_;
  std::vector<double> band_v_;
};

void SpritePass::active(const Snapshot& s, bool moving, Rgb8 time_colour, Out& out,
                        std::size_t i) const {
  if (!s.active[i] && !(moving && s.velocity[i].squaredNorm() > 0)) return;
  const std::vector<double>& values = keep_.values;
  if (profile_ && s.active[i]) {
    out.band_x.push_back(s.position[i]);
    // As field_values computes a (scaled) speed, so the inset is the same either way.
    if (speed_values_)
      out.band_v.push_back(values[i]);
    else
      out.band_v.push_back(scaled_inset_ ? s.velocity[i].norm() / sc_.v_rms : s.velocity[i].norm());
  }
  if (sc_.overlay || by_type_ || std::isnan(values[i])) {
    const Rgb8 c = sc_.overlay ? time_colour
                   : by_type_  ? overlay_colour(s.type[i])
                               : sc_.palette.inactive;
    push(out, wrap_(s.position[i]), s.radius[i], c, std::nanf(""));
    return;
  }
  const double t = normalise(values[i], sc_.range, sc_.style.scale);
  push(out, wrap_(s.position[i]), s.radius[i], cmap_.at8(t), static_cast<float>(t));
}

// A pass over particles [0, n) on the frame's threads: each takes a consecutive piece and sorts
// its sprites into those drawn under the others (inactive ones) and the rest, in vectors of its
// own, and the scene gets, in piece order, everyone's under sprites and then everyone's others:
// the scene is the same whatever the threads, and one pass over a snapshot makes both layers.
template <class Visit>
void SpritePass::in_order(std::size_t n, Visit&& visit) {
  constexpr std::size_t kParticlesPerThread = 50000;
  const int threads = frame_threads(n, kParticlesPerThread);
  auto& pieces = keep_.pieces;
  if (pieces.size() < static_cast<std::size_t>(threads)) pieces.resize(threads);
  run_on_threads(threads, [&](int t) {
    const auto [first, last] = piece(n, threads, t);
    SceneScratch::Piece& mine = pieces[t];
    // Grown, never shrunk: a movie's frames write into the same memory.
    for (auto* v : {&mine.under_sprites, &mine.sprites})
      if (v->size() < last - first) v->resize(last - first);
    for (auto* v : {&mine.under_shade, &mine.shade})
      if (v->size() < last - first) v->resize(last - first);
    mine.under_count = mine.count = 0;
    mine.band_x.clear();
    mine.band_v.clear();
    Out under{mine.under_sprites.data(), mine.under_shade.data(), mine.under_count, mine.band_x,
              mine.band_v};
    Out over{mine.sprites.data(), mine.shade.data(), mine.count, mine.band_x, mine.band_v};
    for (std::size_t i = first; i < last; ++i) visit(under, over, i);
  });
  auto append = [](auto& to, const auto& from, std::size_t count) {
    to.insert(to.end(), from.begin(), from.begin() + static_cast<std::ptrdiff_t>(count));
  };
  for (int t = 0; t < threads; ++t) {
    append(sc_.sprites, pieces[t].under_sprites, pieces[t].under_count);
    append(sc_.shade, pieces[t].under_shade, pieces[t].under_count);
  }
  for (int t = 0; t < threads; ++t) {
    append(sc_.sprites, pieces[t].sprites, pieces[t].count);
    append(sc_.shade, pieces[t].shade, pieces[t].count);
    append(band_x_, pieces[t].band_x, pieces[t].band_x.size());
    append(band_v_, pieces[t].band_v, pieces[t].band_v.size());
  }
}

void SpritePass::run(const std::vector<const Snapshot*>& snaps) {
  std::size_t most = 0;
  for (const Snapshot* s : snaps) most += s->size();
  sc_.sprites = std::move(keep_.sprites);
  sc_.shade = std::move(keep_.shade);
  sc_.sprites.clear();
  sc_.shade.clear();
  sc_.sprites.reserve(most);
  sc_.shade.reserve(most);
  // The inset's profile reads the active particles from a copy made in the pass, which reads
  // them anyway: a pass of its own over a snapshot of 2.5e5 for 2e4 active particles cost a
  // quarter of a frame (bench render/inset_cost). Every active particle goes in, drawn or culled,
  // so a 3D slab's inset is the whole shell's profile. Coloured by a speed, the copy takes the
  // speed from the field's values, read in this pass anyway: reading each velocity again missed
  // the cache once per particle, most of the inset's cost.
  if (profile_) {
    const auto& active = snaps.front()->active;
    const auto n = active.size() - std::count(active.begin(), active.end(), 0);
    band_x_.reserve(n);
    band_v_.reserve(n);
  }
  // Before the first collision nothing is active (DESIGN: active = has collided), but the
  // kicked particle moves: it is drawn, so that no frame of a kick is empty.
  auto moving_instead = [](const Snapshot& s) { return !any_active(s) && s.has_velocity(); };
  // Inactive particles (if shown; of the last snapshot only, in an overlay) lie under the rest.
  if (sc_.style.show_inactive && !sc_.overlay) {
    const Snapshot& s = *snaps.front();
    const bool moving = moving_instead(s);
    in_order(s.size(), [&](Out& under, Out& over, std::size_t i) {
      if (!s.active[i]) inactive(s, under, i);
      active(s, moving, Rgb8{}, over, i);
    });
  } else {
    if (sc_.style.show_inactive) {
      const Snapshot& s = *snaps.back();
      in_order(s.size(), [&](Out& under, Out&, std::size_t i) {
        if (!s.active[i]) inactive(s, under, i);
      });
    }
    for (std::size_t k = 0; k < snaps.size(); ++k) {
      const Snapshot& s = *snaps[k];
      const bool moving = moving_instead(s);
      in_order(s.size(), [&](Out&, Out& over, std::size_t i) {
        active(s, moving, overlay_colour(k), over, i);
      });
    }
  }
  if (profile_) sc_.inset = inset_profile(sc_.dim, band_x_, band_v_, scaled_inset_);
}

}  // namespace

Scene build_scene(const std::vector<const Snapshot*>& snaps, const Style& style, const View& view,
                  OverlayPainter& painter, SceneScratch* scratch) {
  check_style(style);
  GS_CHECK(!snaps.empty());
  Scene sc;
  sc.style = style;
  sc.dim = snaps.front()->info.dim;
  for (const Snapshot* s : snaps)
    if (s->info.dim != sc.dim)
      throw UserError("snapshots of different dimensions cannot share a picture");
  sc.overlay = snaps.size() > 1;
  sc.palette = palette(style.background);
  SceneScratch own;
  SceneScratch& keep = scratch ? *scratch : own;

  colour_scale(sc, snaps, keep.values);
  const Reserve reserve = overlay_reserve(sc, view, painter);
  const BoxWrap wrap(snaps, view.framing, sc.dim);
  for (const Snapshot* s : snaps)
    for (double r : s->radius) sc.r_max = std::max(sc.r_max, r);
  const Subject sub =
      subject(snaps, view.region && wrap.on() ? *view.region : framed_region(snaps, wrap),
              wrap.on(), sc.dim, sc.r_max);
  if (style.box_outline && snaps.front()->info.has_box()) {
    const SnapshotInfo& in = snaps.front()->info;
    sc.box = Eigen::AlignedBox3d(in.origin, in.origin + in.box);
  }
  // Overlays never lie over particles: an explicitly centred view (not a shot) has none reserved.
  const bool placed = !view.centre || reserve.shot;
  Panels panels;
  if (placed) {
    panels.fixed = overlay_panels(sc, view, reserve.shot, painter);
    panels.scale_bar = style.scale_bar;
    panels.below_top = sc.inset ? painter.inset_panel(view.width, view.height).y0 : -1;
    panels.painter = &painter;
  }
  sc.camera = frame_clear_of(sub, view, reserve, panels);
  SpritePass(sc, keep, wrap, *snaps.front()).run(snaps);
  if (sc.dim == 3 && style.occlusion_cull) cull_occluded(sc);
  return sc;
}

}  // namespace gs::render
