#include "render/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

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
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      for (int k = 0; k < 3; ++k)
        p[k] = static_cast<std::uint8_t>(p[k] + alpha * (colour[k] - p[k]) + 0.5f);
    }
}

int OverlayPainter::unit(int width, int height) {
  const int px = std::clamp(static_cast<int>(std::lround(std::min(width, height) / 40.0)), 10, 72);
  font_.set_pixel_size(px);
  return px;
}

OverlayPainter::BarLayout OverlayPainter::layout(int width, int height,
                                                 std::pair<double, double> range, Scale scale,
                                                 const std::string& label) {
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
  const int title_w = font_.width(label);
  l.right = width - u;
  l.bar.x1 = l.right - label_w - l.gap - l.tick_len;
  l.bar.x0 = l.bar.x1 - bar_w;
  l.bar.y0 = (height - bar_h) / 2 + u / 2;
  l.bar.y1 = l.bar.y0 + bar_h;
  l.title_base = l.bar.y0 - u / 2 - font_.descent();
  l.title_x = std::min(l.bar.x0, l.right - title_w);
  l.panel_x0 = std::min(l.bar.x0, l.title_x) - u / 2;
  l.bar.panel_x0 = l.panel_x0;
  return l;
}

int OverlayPainter::colorbar_width(int width, int height, std::pair<double, double> range,
                                   Scale scale, const std::string& label) {
  return width - layout(width, height, range, scale, label).panel_x0;
}

BarRect OverlayPainter::colorbar(Image& img, const Colormap& cmap, std::pair<double, double> range,
                                 Scale scale, const std::string& label, const OverlayColours& c) {
  const BarLayout l = layout(img.width, img.height, range, scale, label);
  const int u = l.u, tick_len = l.tick_len, gap = l.gap, bar_h = l.bar.y1 - l.bar.y0;
  const BarRect r = l.bar;
  const auto& ticks = l.ticks;
  fill_rect(img, l.panel_x0, l.title_base - font_.ascent() - u / 3, l.right + u / 2,
            r.y1 + u / 2 + font_.descent(), c.panel, 0.8f);
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
  return r;
}

void OverlayPainter::top_left_label(Image& img, const std::string& text, const OverlayColours& c) {
  const int u = unit(img.width, img.height);
  const int w = font_.width(text);
  fill_rect(img, u / 2, u / 2, u + w + u / 2, u + font_.ascent() + font_.descent() + u / 3, c.panel,
            0.8f);
  font_.draw(img, u, u + font_.ascent(), text, c.text);
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

void OverlayPainter::scale_bar(Image& img, double pixels_per_unit, const OverlayColours& c) {
  const int u = unit(img.width, img.height);
  const double len = nice_step(img.width / pixels_per_unit, 5);  // about a fifth of the width
  const int px = static_cast<int>(std::lround(len * pixels_per_unit));
  const std::string text = tick_text(len) + " diameters";
  const int th = std::max(2, u / 5);
  const int y = img.height - u;
  fill_rect(img, u / 2, y - font_.ascent() - font_.descent() - u / 2,
            u + std::max(px, font_.width(text)) + u / 2, y + th + u / 2, c.panel, 0.8f);
  fill_rect(img, u, y, u + px, y + th, c.text);
  font_.draw(img, u, y - u / 4 - font_.descent(), text, c.text);
}

}  // namespace gs::render
