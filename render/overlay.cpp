#include "render/overlay.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "render/field.h"

namespace gs::render {
namespace {

double nice_step(double span, int target) {
  const double raw = span / target;
  const double mag = std::pow(10, std::floor(std::log10(raw)));
  const double f = raw / mag;
  return (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10) * mag;
}

}  // namespace

std::vector<double> colorbar_ticks(double lo, double hi, Scale scale) {
  std::vector<double> t;
  if (scale == Scale::Log && lo > 0) {
    for (const double m : {1.0, 0.0}) {  // first decades only, then 1-2-5 if too few
      t.clear();
      for (int e = static_cast<int>(std::floor(std::log10(lo))) - 1;
           e <= static_cast<int>(std::ceil(std::log10(hi))); ++e)
        for (const double k : m == 1.0 ? std::vector<double>{1} : std::vector<double>{1, 2, 5}) {
          const double v = k * std::pow(10.0, e);
          if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) t.push_back(v);
        }
      if (t.size() >= 3) return t;
    }
    if (t.size() >= 2) return t;
  }
  const double step = nice_step(hi - lo, 5);
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + step * 1e-9; k += 1)
    t.push_back(std::abs(k) < 1e-9 ? 0.0 : k * step);
  return t;
}

std::string tick_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

void fill_rect(Image& img, int x0, int y0, int x1, int y1, Rgb8 colour, float alpha) {
  x0 = std::max(x0, 0), y0 = std::max(y0, 0);
  x1 = std::min(x1, img.width), y1 = std::min(y1, img.height);
  if (x0 >= x1 || y0 >= y1) return;
  if (alpha >= 1) {  // most calls: the inset's lines and dots, ticks, a bar's rows
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) std::copy_n(colour.data(), 3, img.pixel(x, y));
    return;
  }
  // The blend of a channel depends on its old value alone: a table of 3 x 256 makes a panel
  // (the inset's is a sixth of a 1080p frame) three look-ups a pixel.
  std::array<std::array<std::uint8_t, 256>, 3> blend;
  for (int k = 0; k < 3; ++k)
    for (int v = 0; v < 256; ++v)
      blend[k][v] = static_cast<std::uint8_t>(v + alpha * (colour[k] - v) + 0.5f);
  // A pixel already of the panel's colour keeps it (the blend of c over c is c). Panels are
  // painted on the background colour, and pictures keep their particles clear of them, so most
  // runs of opaque pixels of that colour are skipped, told by one memcmp.
  constexpr int kRun = 32;
  std::array<std::uint8_t, 4 * kRun> same;
  for (int i = 0; i < kRun; ++i)
    std::copy_n(std::array<std::uint8_t, 4>{colour[0], colour[1], colour[2], 255}.data(), 4,
                same.data() + 4 * i);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; x += kRun) {
      const int n = std::min(kRun, x1 - x);
      std::uint8_t* p = img.pixel(x, y);
      if (std::memcmp(p, same.data(), 4 * static_cast<std::size_t>(n)) == 0) continue;
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) p[4 * i + k] = blend[k][p[4 * i + k]];
    }
}

int OverlayPainter::unit(int width, int height) {
  const int px = std::clamp(static_cast<int>(std::lround(std::min(width, height) / 40.0)), 10, 72);
  font_.set_pixel_size(px);
  return px;
}

OverlayPainter::BarLayout OverlayPainter::layout(int width, int height,
                                                 std::pair<double, double> range, Scale scale,
                                                 const std::string& label,
                                                 const std::string& note) {
  BarLayout l;
  l.u = unit(width, height);
  const int u = l.u;
  l.ticks = colorbar_ticks(range.first, range.second, scale);
  int label_w = 0;
  for (double v : l.ticks) label_w = std::max(label_w, font_.width(tick_text(v)));
  const int bar_w = std::max(6, u * 4 / 5);
  l.tick_len = std::max(3, u / 3);
  l.gap = u / 4;
  const int bar_h = std::max(20, height / 2);
  const int title_w = std::max(font_.width(label), font_.width(note));
  l.right = width - u;
  l.bar.x1 = l.right - label_w - l.gap - l.tick_len;
  l.bar.x0 = l.bar.x1 - bar_w;
  l.bar.y0 = (height - bar_h) / 2 + u / 2;
  l.bar.y1 = l.bar.y0 + bar_h;
  l.title_base = l.bar.y0 - u / 2 - font_.descent();
  l.title_x = std::min(l.bar.x0, l.right - title_w);
  l.note_base = note.empty() ? l.bar.y1 : l.bar.y1 + u / 2 + font_.ascent();
  l.panel_x0 = std::min(l.bar.x0, l.title_x) - u / 2;
  l.bar.panel_x0 = l.panel_x0;
  return l;
}

int OverlayPainter::colorbar_width(int width, int height, std::pair<double, double> range,
                                   Scale scale, const std::string& label, const std::string& note) {
  return width - layout(width, height, range, scale, label, note).panel_x0;
}

BarRect OverlayPainter::colorbar(Image& img, const Colormap& cmap, std::pair<double, double> range,
                                 Scale scale, const std::string& label, const std::string& note,
                                 const OverlayColours& c) {
  const BarLayout l = layout(img.width, img.height, range, scale, label, note);
  const int u = l.u, tick_len = l.tick_len, gap = l.gap, bar_h = l.bar.y1 - l.bar.y0;
  const BarRect r = l.bar;
  const auto& ticks = l.ticks;
  fill_rect(img, l.panel_x0, l.title_base - font_.ascent() - u / 3, l.right + u / 2,
            l.note_base + u / 2 + font_.descent(), c.panel, 0.8f);
  for (int y = r.y0; y < r.y1; ++y) {
    const double t = bar_h > 1 ? double(r.y1 - 1 - y) / (bar_h - 1) : 0;
    fill_rect(img, r.x0, y, r.x1, y + 1, cmap.at8(t));
  }
  // Frame of one pixel around the gradient, outside it so the end colours stay pure.
  fill_rect(img, r.x0 - 1, r.y0 - 1, r.x1 + 1, r.y0, c.text);
  fill_rect(img, r.x0 - 1, r.y1, r.x1 + 1, r.y1 + 1, c.text);
  fill_rect(img, r.x0 - 1, r.y0, r.x0, r.y1, c.text);
  fill_rect(img, r.x1, r.y0, r.x1 + 1, r.y1, c.text);
  for (double v : ticks) {
    const double t = normalise(v, range, scale);
    const int y = r.y1 - 1 - static_cast<int>(std::lround(t * (bar_h - 1)));
    fill_rect(img, r.x1, y, r.x1 + tick_len, y + 1 + u / 16, c.text);
    font_.draw(img, r.x1 + tick_len + gap, y + (font_.ascent() - font_.descent()) / 2, tick_text(v),
               c.text);
  }
  font_.draw(img, l.title_x, l.title_base, label, c.text);
  if (!note.empty()) font_.draw(img, l.title_x, l.note_base, note, c.text);
  return r;
}

Rect OverlayPainter::top_left_label_panel(int width, int height, const std::string& text) {
  const int u = unit(width, height);
  const int w = font_.width(text);
  return {u / 2, u / 2, u + w + u / 2, u + font_.ascent() + font_.descent() + u / 3};
}

Rect OverlayPainter::top_left_label(Image& img, const std::string& text, const OverlayColours& c) {
  const Rect r = top_left_label_panel(img.width, img.height, text);
  const int u = unit(img.width, img.height);
  fill_rect(img, r.x0, r.y0, r.x1, r.y1, c.panel, 0.8f);
  font_.draw(img, u, u + font_.ascent(), text, c.text);
  return r;
}

int OverlayPainter::legend_width(int width, int height,
                                 const std::vector<std::pair<Rgb8, std::string>>& entries) {
  const int u = unit(width, height);
  int w = 0;
  for (const auto& e : entries) w = std::max(w, font_.width(e.second));
  return u + w + font_.ascent() + u;
}

int OverlayPainter::legend_height(int width, int height, std::size_t entries) {
  const int u = unit(width, height);
  return u + (font_.ascent() + font_.descent() + u / 4) * static_cast<int>(entries) + u / 3 + u / 2;
}

void OverlayPainter::legend(Image& img, const std::vector<std::pair<Rgb8, std::string>>& entries,
                            const OverlayColours& c) {
  const int u = unit(img.width, img.height);
  const int line = font_.ascent() + font_.descent() + u / 4;
  int w = 0;
  for (const auto& e : entries) w = std::max(w, font_.width(e.second));
  const int box = font_.ascent();
  const int x0 = img.width - u - w - box - u / 2;
  fill_rect(img, x0 - u / 2, u / 2, img.width - u / 2,
            u + line * static_cast<int>(entries.size()) + u / 3, c.panel, 0.8f);
  int y = u;
  for (const auto& [colour, text] : entries) {
    fill_rect(img, x0, y, x0 + box, y + box, colour);
    font_.draw(img, x0 + box + u / 2, y + font_.ascent(), text, c.text);
    y += line;
  }
}

Rect OverlayPainter::scale_bar_panel(int width, int height, double pixels_per_unit,
                                     int below_top) {
  const int u = unit(width, height);
  const double len = nice_step(width / pixels_per_unit, 5);  // about a fifth of the width
  const int px = static_cast<int>(std::lround(len * pixels_per_unit));
  const std::string text = tick_text(len) + " diameters";
  const int th = std::max(2, u / 5);
  const int y = (below_top >= 0 ? below_top : height) - u;
  return {u / 2, y - font_.ascent() - font_.descent() - u / 2,
          u + std::max(px, font_.width(text)) + u / 2, y + th + u / 2};
}

Rect OverlayPainter::scale_bar(Image& img, double pixels_per_unit, const OverlayColours& c,
                               int below_top) {
  const Rect r = scale_bar_panel(img.width, img.height, pixels_per_unit, below_top);
  const int u = unit(img.width, img.height);
  const double len = nice_step(img.width / pixels_per_unit, 5);
  const int px = static_cast<int>(std::lround(len * pixels_per_unit));
  const std::string text = tick_text(len) + " diameters";
  const int th = std::max(2, u / 5);
  const int y = (below_top >= 0 ? below_top : img.height) - u;
  fill_rect(img, r.x0, r.y0, r.x1, r.y1, c.panel, 0.8f);
  fill_rect(img, u, y, u + px, y + th, c.text);
  font_.draw(img, u, y - u / 4 - font_.descent(), text, c.text);
  return r;
}

void draw_line(Image& img, double x0, double y0, double x1, double y1, Rgb8 colour, double width) {
  const double len = std::hypot(x1 - x0, y1 - y0);
  const int steps = std::max(1, static_cast<int>(std::ceil(len * 2)));
  const int w = std::max(1, static_cast<int>(std::lround(width)));
  for (int k = 0; k <= steps; ++k) {
    const double f = double(k) / steps;
    const int x = static_cast<int>(std::lround(x0 + f * (x1 - x0) - 0.5 * (w - 1)));
    const int y = static_cast<int>(std::lround(y0 + f * (y1 - y0) - 0.5 * (w - 1)));
    fill_rect(img, x, y, x + w, y + w, colour);
  }
}

Rect OverlayPainter::inset_panel(int width, int height) {
  const int u = unit(width, height);
  const int side = std::min(width, height);
  const int h = std::max(100, side * 3 / 10), w = std::max(160, h * 8 / 5);
  return {u / 2, height - u / 2 - h, u / 2 + w, height - u / 2};
}

int OverlayPainter::inset_width(int width, int height) {
  return inset_panel(width, height).x1 + unit(width, height) / 2;
}

Rect OverlayPainter::inset(Image& img, const InsetData& d, const Colormap& cmap,
                           std::pair<double, double> range, Scale scale, const OverlayColours& c) {
  const Rect panel = inset_panel(img.width, img.height);
  const int u = unit(img.width, img.height);
  const int small = std::max(9, u * 7 / 10);
  font_.set_pixel_size(small);
  fill_rect(img, panel.x0, panel.y0, panel.x1, panel.y1, c.panel, 0.85f);
  if (d.r.empty()) return panel;
  // Axes: y ranges start at 0; nice ticks, at most about four on each axis.
  double n_max = 0, v_max = 0;
  for (std::size_t b = 0; b < d.r.size(); ++b) {
    n_max = std::max(n_max, d.density[b]);
    if (std::isfinite(d.speed[b])) v_max = std::max(v_max, d.speed[b]);
  }
  auto axis = [](double top) {
    top = top > 0 ? top : 1;
    const double step = nice_step(top, 2);
    return std::pair{std::ceil(top / step - 1e-9) * step, step};
  };
  const auto [n_top, n_step] = axis(n_max);
  const auto [v_top, v_step] = axis(v_max);
  const auto [r_top, r_step] = axis(d.r_max);
  auto label_w = [&](double top, double step) {
    int lw = 0;
    for (double v = 0; v <= top + step * 1e-9; v += step)
      lw = std::max(lw, font_.width(tick_text(v)));
    return lw;
  };
  const int tick = std::max(2, small / 4), gap = std::max(2, small / 4);
  const int line = font_.ascent() + font_.descent();
  const Rect plot{panel.x0 + gap * 2 + label_w(n_top, n_step) + tick, panel.y0 + gap + line + gap,
                  panel.x1 - gap * 2 - label_w(v_top, v_step) - tick,
                  panel.y1 - gap - 2 * line - tick};
  if (plot.empty()) return panel;
  const double pw = plot.x1 - plot.x0, ph = plot.y1 - plot.y0;
  auto X = [&](double r) { return plot.x0 + r / r_top * pw; };
  auto Yn = [&](double n) { return plot.y1 - n / n_top * ph; };
  auto Yv = [&](double v) { return plot.y1 - v / v_top * ph; };
  const Rgb8 grey = {static_cast<std::uint8_t>((c.text[0] + c.panel[0]) / 2),
                     static_cast<std::uint8_t>((c.text[1] + c.panel[1]) / 2),
                     static_cast<std::uint8_t>((c.text[2] + c.panel[2]) / 2)};
  // Density: one grey column per shell, opaque in the colour the grey at 70% gives over the
  // panel (where the panel lies on the background, as a fitted picture keeps it: the pixels the
  // blend gave, written instead of blended).
  Rgb8 column;
  for (int k = 0; k < 3; ++k)
    column[k] = static_cast<std::uint8_t>(c.panel[k] + 0.7f * (grey[k] - c.panel[k]) + 0.5f);
  const double half_bin = d.r.size() > 1 ? 0.5 * (d.r[1] - d.r[0]) : d.r_max / 2;
  for (std::size_t b = 0; b < d.r.size(); ++b)
    fill_rect(img, static_cast<int>(std::lround(X(d.r[b] - half_bin))),
              static_cast<int>(std::lround(Yn(d.density[b]))),
              static_cast<int>(std::lround(X(d.r[b] + half_bin))), plot.y1, column);
  // Mean speed: a thin line through dots in the colour the particles of that speed have.
  const int dot = std::max(3, small / 3);
  double px = NAN, py = NAN;
  for (std::size_t b = 0; b < d.r.size(); ++b) {
    if (!std::isfinite(d.speed[b])) continue;
    const double x = X(d.r[b]), y = Yv(d.speed[b]);
    if (std::isfinite(px)) draw_line(img, px, py, x, y, c.text, 1);
    px = x, py = y;
  }
  for (std::size_t b = 0; b < d.r.size(); ++b) {
    if (!std::isfinite(d.speed[b])) continue;
    const int x = static_cast<int>(std::lround(X(d.r[b]))),
              y = static_cast<int>(std::lround(Yv(d.speed[b])));
    fill_rect(img, x - dot / 2 - 1, y - dot / 2 - 1, x + dot - dot / 2 + 1, y + dot - dot / 2 + 1,
              c.text);
    fill_rect(img, x - dot / 2, y - dot / 2, x + dot - dot / 2, y + dot - dot / 2,
              cmap.at8(normalise(d.speed[b], range, scale)));
  }
  // Frame, ticks and their labels.
  fill_rect(img, plot.x0 - 1, plot.y0, plot.x0, plot.y1 + 1, c.text);
  fill_rect(img, plot.x1, plot.y0, plot.x1 + 1, plot.y1 + 1, c.text);
  fill_rect(img, plot.x0 - 1, plot.y1, plot.x1 + 1, plot.y1 + 1, c.text);
  const int mid = (font_.ascent() - font_.descent()) / 2;
  for (double v = 0; v <= n_top + n_step * 1e-9; v += n_step) {
    const int y = static_cast<int>(std::lround(Yn(v)));
    fill_rect(img, plot.x0 - 1 - tick, y, plot.x0 - 1, y + 1, c.text);
    const std::string t = tick_text(v);
    font_.draw(img, plot.x0 - 1 - tick - gap - font_.width(t), y + mid, t, c.text);
  }
  for (double v = 0; v <= v_top + v_step * 1e-9; v += v_step) {
    const int y = static_cast<int>(std::lround(Yv(v)));
    fill_rect(img, plot.x1 + 1, y, plot.x1 + 1 + tick, y + 1, c.text);
    font_.draw(img, plot.x1 + 1 + tick + gap, y + mid, tick_text(v), c.text);
  }
  for (double r = 0; r <= r_top + r_step * 1e-9; r += r_step) {
    const int x = static_cast<int>(std::lround(X(r)));
    fill_rect(img, x, plot.y1 + 1, x + 1, plot.y1 + 1 + tick, c.text);
    const std::string t = tick_text(r);
    font_.draw(img, x - font_.width(t) / 2, plot.y1 + tick + gap + font_.ascent(), t, c.text);
  }
  const std::string xl = "r from centre of mass";
  font_.draw(img, (plot.x0 + plot.x1 - font_.width(xl)) / 2, panel.y1 - gap - font_.descent(), xl,
             c.text);
  font_.draw(img, panel.x0 + gap, panel.y0 + gap + font_.ascent(), "density", grey);
  const std::string vl = d.scaled ? "v / v_rms" : "speed";
  font_.draw(img, panel.x1 - gap - font_.width(vl), panel.y0 + gap + font_.ascent(), vl, c.text);
  return panel;
}

}  // namespace gs::render
