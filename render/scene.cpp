#include "render/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

Scene build_scene(const std::vector<const Snapshot*>& snaps, const Style& style, const View& view,
                  OverlayPainter& painter, SceneScratch* scratch) {
  check_style(style);
  GS_CHECK(!snaps.empty());
  Scene sc;
  sc.style = style;
  const Colormap cmap = picture_colormap(style);
  const int dim = sc.dim = snaps.front()->info.dim;
  for (const Snapshot* s : snaps)
    if (s->info.dim != dim)
      throw UserError("snapshots of different dimensions cannot share a picture");
  const bool three_d = dim == 3;
  const bool overlay = sc.overlay = snaps.size() > 1;
  const Palette pal = sc.palette = palette(style.background);

  SceneScratch own;
  SceneScratch& keep = scratch ? *scratch : own;
  // Colours need the field only for a single snapshot; the overlay colours by time.
  std::vector<double>& values = keep.values;
  values.clear();
  if (!overlay) {
    const Snapshot& s = *snaps.front();
    field_values(s, style.field, &sc.v_rms, style.column, values);
    const std::vector<std::uint8_t> all(any_active(s) ? 0 : s.size(), 1);
    const auto& mask = any_active(s) ? s.active : all;
    const auto fixed = style.range_per_frame ? std::nullopt : default_range(style.field, dim);
    sc.range = style.range ? *style.range
               : fixed     ? *fixed
                           : auto_range(values, mask, style.scale, style.percentile_low,
                                        style.percentile_high);
    if (is_scaled(style.field) && sc.v_rms > 0) sc.bar_note = "v_rms = " + fmt("%.3g", sc.v_rms);
    if (style.inset) sc.inset.emplace();  // its profile is taken in the sprite pass below
  }
  sc.bar_label = style.field == Field::Column ? style.column : field_label(style.field);
  if (style.field == Field::None) sc.style.colorbar = false;  // one colour says nothing
  if (style.scale == Scale::Log) sc.bar_label += " (log)";
  sc.time_text = time_text(snaps.front()->info);
  for (std::size_t k = 0; overlay && k < snaps.size(); ++k)
    sc.legend.emplace_back(overlay_colour(k), time_text(snaps[k]->info));

  // A framed (not explicitly centred) scene keeps clear of the colour bar or legend on the
  // right: it is fitted into the rest of the width. A 2D legend goes above the scene instead
  // when that leaves more room (square or tall pictures, a legend too wide to sit beside it).
  int reserve = 0, reserve_top = 0, reserve_left = 0;
  const bool shot = !three_d && view.centre && view.half_width > 0;
  if (!view.centre || shot) {
    if (sc.inset) reserve_left = painter.inset_width(view.width, view.height);
    if (sc.style.colorbar && !overlay)
      reserve = painter.colorbar_width(view.width, view.height, sc.range, style.scale, sc.bar_label,
                                       sc.bar_note);
    else if (style.legend && overlay)
      reserve = painter.legend_width(view.width, view.height, sc.legend);
    if (style.legend && overlay && !three_d) {
      const int top = painter.legend_height(view.width, view.height, sc.legend.size());
      if (top < view.height / 2 &&
          std::min(view.width, view.height - top) > std::min(view.width - reserve, view.height)) {
        reserve = 0;
        reserve_top = top;
      }
    }
    if (reserve + reserve_left >= view.width / 2) reserve = reserve_left = 0;
  }
  // The scene is fitted between the inset on the left and the colour bar on the right.
  const int narrow_by = reserve + reserve_left, shift_px = reserve - reserve_left;

  // Framing: the active particles of all snapshots, or the box.
  Eigen::AlignedBox3d fit;
  // The box of the first snapshot that has one (rectangular: each axis its own edge).
  const SnapshotInfo* boxed = nullptr;
  for (const Snapshot* s : snaps)
    if (!boxed && s->info.has_box()) boxed = &s->info;
  const bool wrap = view.framing == Framing::Box && boxed;
  // Below `inside` (a hair under the edge) x / edge rounds below 1, its floor is 0 and the
  // wrap leaves origin + x: the division, the slowest step of a frame's scene, is skipped for
  // the particles already in the box, with the same bits.
  Eigen::Vector3d inside = Eigen::Vector3d::Constant(-1);
  if (boxed && boxed->box.allFinite()) inside = boxed->box * (1 - 0x1p-50);
  // Axis by axis in registers: a loop over the axes of a copy in memory, read back whole, stalled
  // every particle on the stores it had not yet forwarded (a third of the scene's time).
  auto wrap_axis = [&](double p, int k) {
    const double x = p - boxed->origin[k], edge = boxed->box[k];
    return x >= 0 && x <= inside[k] ? boxed->origin[k] + x
                                    : boxed->origin[k] + x - edge * std::floor(x / edge);
  };
  auto wrapped = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    if (!wrap) return p;
    return {wrap_axis(p.x(), 0), dim > 1 ? wrap_axis(p.y(), 1) : p.y(),
            dim > 2 ? wrap_axis(p.z(), 2) : p.z()};
  };
  if (wrap) {
    fit.extend(boxed->origin);
    fit.extend(boxed->origin + boxed->box);
  }
  for (int pass = 0; pass < 2 && fit.isEmpty(); ++pass)
    for (const Snapshot* s : snaps)
      for (std::size_t i = 0; i < s->size(); ++i)
        if (pass == 1 || s->active[i]) fit.extend(wrapped(s->position[i]));
  double r_max = 0;
  for (const Snapshot* s : snaps)
    for (double r : s->radius) r_max = std::max(r_max, r);
  sc.r_max = r_max;
  Camera& cam = sc.camera;
  if (three_d) {
    // Bounding sphere about the box's centre: tighter than the box's corners for a shell.
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
    cam = make_camera_3d(c, std::sqrt(r2) + r_max, view);
    if (narrow_by > 0) {
      View narrow = view;
      narrow.width -= narrow_by;
      const Camera fitted = make_camera_3d(c, std::sqrt(r2) + r_max, narrow);
      View shifted = view;
      shifted.distance = fitted.distance;
      const double ppu = view.height / (2 * fitted.distance * fitted.tan_half_y);
      shifted.centre = c + fitted.view.block<1, 3>(0, 0).transpose() * (shift_px / 2.0 / ppu);
      cam = make_camera_3d(c, std::sqrt(r2) + r_max, shifted);
    }
  } else {
    // Fitted into the part of the picture left free, then widened to the whole picture.
    View open_area = view;
    open_area.width -= narrow_by;
    open_area.height -= reserve_top;
    cam = make_camera_2d(fit, r_max, open_area);
    if (shot) {
      const double half_h = view.half_width * view.height / view.width;
      const double ppu_shot =
          std::min(open_area.width / (2 * view.half_width), open_area.height / (2 * half_h));
      cam.half_w = open_area.width / (2 * ppu_shot);
      cam.half_h = open_area.height / (2 * ppu_shot);
    }
    const double ppu = cam.pixels_per_unit();
    if (narrow_by > 0) {
      cam.width = view.width;
      cam.half_w = view.width / (2 * ppu);
      cam.origin.x() += shift_px / (2 * ppu);
    }
    if (reserve_top > 0) {
      cam.height = view.height;
      cam.half_h = view.height / (2 * ppu);
      cam.origin.y() += reserve_top / (2 * ppu);  // world y points up the picture
    }
  }

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
  auto push = [&](Out& out, const Eigen::Vector3d& p, double r, Rgb8 c, float shade) {
    if (!cam.visible(p, r)) return;
    const Eigen::Vector3d d = p - cam.origin;
    out.sprites[out.count] = {static_cast<float>(d.x()),
                              static_cast<float>(d.y()),
                              static_cast<float>(three_d ? d.z() : 0.0),
                              static_cast<float>(r),
                              {c[0], c[1], c[2], 255}};
    out.shade[out.count++] = shade;
  };
  std::size_t most = 0;
  for (const Snapshot* s : snaps) most += s->size();
  sc.sprites = std::move(keep.sprites);
  sc.shade = std::move(keep.shade);
  sc.sprites.clear();
  sc.shade.clear();
  sc.sprites.reserve(most);
  sc.shade.reserve(most);
  const float none = std::nanf("");
  // The inset's profile reads the active particles from a copy made in the pass below, which
  // reads them anyway: a pass of its own over a snapshot of 2.5e5 for 2e4 active particles cost
  // a quarter of a frame (bench render/inset_cost). Every active particle goes in, drawn or
  // culled, so a 3D slab's inset is the whole shell's profile. Coloured by a speed, the copy
  // takes the speed from `values`, read in this pass anyway: reading each velocity again missed
  // the cache once per particle, most of the inset's cost.
  std::vector<Eigen::Vector3d> band_x;
  std::vector<double> band_v;
  const bool profile = sc.inset && snaps.front()->has_velocity();
  const bool speed_values = style.field == Field::Speed || style.field == Field::ScaledSpeed;
  const bool scaled_inset = is_scaled(style.field) && sc.v_rms > 0;
  if (profile) {
    const auto& active = snaps.front()->active;
    const auto n = active.size() - std::count(active.begin(), active.end(), 0);
    band_x.reserve(n);
    band_v.reserve(n);
  }
  // A pass over particles [0, n) on the frame's threads: each takes a consecutive piece and
  // sorts its sprites into those drawn under the others (inactive ones) and the rest, in vectors
  // of its own, and the scene gets, in piece order, everyone's under sprites and then everyone's
  // others: the scene is the same whatever the threads, and one pass over a snapshot makes both
  // layers.
  auto in_order = [&](std::size_t n, auto&& visit) {
    constexpr std::size_t kParticlesPerThread = 50000;
    const int threads = frame_threads(n, kParticlesPerThread);
    auto& pieces = keep.pieces;
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
      append(sc.sprites, pieces[t].under_sprites, pieces[t].under_count);
      append(sc.shade, pieces[t].under_shade, pieces[t].under_count);
    }
    for (int t = 0; t < threads; ++t) {
      append(sc.sprites, pieces[t].sprites, pieces[t].count);
      append(sc.shade, pieces[t].shade, pieces[t].count);
      append(band_x, pieces[t].band_x, pieces[t].band_x.size());
      append(band_v, pieces[t].band_v, pieces[t].band_v.size());
    }
  };
  auto inactive = [&](const Snapshot& s, Out& out, std::size_t i) {
    push(out, wrapped(s.position[i]), s.radius[i], pal.inactive, none);
  };
  // Before the first collision nothing is active (DESIGN: active = has collided), but the
  // kicked particle moves: it is drawn, so that no frame of a kick is empty.
  auto moving_instead = [](const Snapshot& s) { return !any_active(s) && s.has_velocity(); };
  auto active = [&](const Snapshot& s, bool moving, Rgb8 time_colour, Out& out, std::size_t i) {
    if (!s.active[i] && !(moving && s.velocity[i].squaredNorm() > 0)) return;
    if (profile && s.active[i]) {
      out.band_x.push_back(s.position[i]);
      // As field_values computes a (scaled) speed, so the inset is the same either way.
      if (speed_values)
        out.band_v.push_back(values[i]);
      else
        out.band_v.push_back(scaled_inset ? s.velocity[i].norm() / sc.v_rms : s.velocity[i].norm());
    }
    if (overlay || std::isnan(values[i])) {
      push(out, wrapped(s.position[i]), s.radius[i], overlay ? time_colour : pal.inactive, none);
      return;
    }
    const double t = normalise(values[i], sc.range, style.scale);
    push(out, wrapped(s.position[i]), s.radius[i], cmap.at8(t), static_cast<float>(t));
  };
  // Inactive particles (if shown; of the last snapshot only, in an overlay) lie under the rest.
  if (style.show_inactive && !overlay) {
    const Snapshot& s = *snaps.front();
    const bool moving = moving_instead(s);
    in_order(s.size(), [&](Out& under, Out& over, std::size_t i) {
      if (!s.active[i]) inactive(s, under, i);
      active(s, moving, Rgb8{}, over, i);
    });
  } else {
    if (style.show_inactive) {
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
  if (profile) sc.inset = inset_profile(dim, band_x, band_v, scaled_inset);
  if (three_d && style.occlusion_cull) cull_occluded(sc);
  return sc;
}

}  // namespace gs::render
