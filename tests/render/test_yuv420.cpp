// The movie's colour conversion against BT.709's formulas evaluated in double.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "render/yuv420.h"

namespace gs::render {
namespace {

struct Exact {
  double y, cb, cr;
};
// ITU-R BT.709-6, Table 3, limited range, from 8-bit full-range R'G'B'.
Exact bt709(double r, double g, double b) {
  r /= 255, g /= 255, b /= 255;
  const double ey = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  return {16 + 219 * ey, 128 + 224 * (b - ey) / 1.8556, 128 + 224 * (r - ey) / 1.5748};
}

TEST(Yuv420, EverySampleIsBt709RoundedToTheNearest) {
  const int w = 64, h = 48;
  Image img(w, h);
  std::mt19937 rng(5);
  for (auto& c : img.rgba) c = static_cast<std::uint8_t>(rng());
  // Pure colours and greys in the first row, where a wrong matrix shows most.
  const std::uint8_t pure[][3] = {
      {255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}, {0, 0, 0}};
  for (int k = 0; k < 5; ++k)
    for (int c = 0; c < 3; ++c)
      img.pixel(2 * k, 0)[c] = img.pixel(2 * k + 1, 0)[c] = img.pixel(2 * k, 1)[c] =
          img.pixel(2 * k + 1, 1)[c] = pure[k][c];
  const int ys = w + 8, cs = w / 2 + 4;  // strides wider than the rows, as libavcodec's are
  std::vector<std::uint8_t> y(ys * h), cb(cs * h / 2), cr(cs * h / 2);
  rgba_to_yuv420(img, y.data(), ys, cb.data(), cr.data(), cs);
  double worst = 0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const std::uint8_t* p = img.pixel(i, j);
      worst = std::max(worst, std::abs(y[j * ys + i] - bt709(p[0], p[1], p[2]).y));
    }
  for (int j = 0; j < h / 2; ++j)
    for (int i = 0; i < w / 2; ++i) {
      double r = 0, g = 0, b = 0;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const std::uint8_t* p = img.pixel(2 * i + dx, 2 * j + dy);
          r += p[0] / 4.0, g += p[1] / 4.0, b += p[2] / 4.0;
        }
      const Exact e = bt709(r, g, b);
      worst = std::max({worst, std::abs(cb[j * cs + i] - e.cb), std::abs(cr[j * cs + i] - e.cr)});
    }
  EXPECT_LT(worst, 0.52);  // rounding to the nearest, up to the coefficients' 16 bits
  // Pure red, green, blue, white and black (BT.601 would give red 81, green 145).
  const int luma[] = {63, 173, 32, 235, 16};
  for (int k = 0; k < 5; ++k) EXPECT_EQ(y[2 * k], luma[k]) << k;
  EXPECT_EQ(cb[0], 102);
  EXPECT_EQ(cr[0], 240);
}

}  // namespace
}  // namespace gs::render
