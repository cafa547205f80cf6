#include "render/image_compare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "sim/error.h"

namespace gs::render {
namespace {

bool differs(const std::uint8_t* a, const std::uint8_t* b, int tolerance) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(int(a[k]) - int(b[k])) > tolerance) return true;
  return false;
}

std::vector<float> luma(const Image& img) {
  std::vector<float> y(static_cast<std::size_t>(img.width) * img.height);
  for (std::size_t i = 0; i < y.size(); ++i) {
    const std::uint8_t* p = &img.rgba[4 * i];
    y[i] = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
  }
  return y;
}

// SSIM of one window from its means, variances and covariance (Wang et al. 2004, eq. 13).
double ssim_of(double mu_a, double mu_b, double var_a, double var_b, double cov) {
  constexpr double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  return ((2 * mu_a * mu_b + c1) * (2 * cov + c2)) /
         ((mu_a * mu_a + mu_b * mu_b + c1) * (var_a + var_b + c2));
}

}  // namespace

double psnr_of_mse(double mse) {
  return mse == 0 ? std::numeric_limits<double>::infinity() : 10 * std::log10(255.0 * 255.0 / mse);
}

double ssim(const Image& a, const Image& b) {
  GS_CHECK(a.width == b.width && a.height == b.height);
  const int w = a.width, h = a.height;
  if (w == 0 || h == 0) return 1;
  const std::vector<float> ya = luma(a), yb = luma(b);
  constexpr int K = 11;
  if (w < K || h < K) {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (std::size_t i = 0; i < ya.size(); ++i) {
      sa += ya[i], sb += yb[i], saa += ya[i] * ya[i], sbb += yb[i] * yb[i], sab += ya[i] * yb[i];
    }
    const double n = double(ya.size()), ma = sa / n, mb = sb / n;
    return ssim_of(ma, mb, saa / n - ma * ma, sbb / n - mb * mb, sab / n - ma * mb);
  }
  std::array<float, K> g;
  float gsum = 0;
  for (int k = 0; k < K; ++k)
    gsum += g[k] = std::exp(-float((k - 5) * (k - 5)) / (2 * 1.5f * 1.5f));
  for (float& v : g) v /= gsum;

  // The window is separable: filter each row horizontally into a ring of the last K rows (five
  // moments: a, b, a^2, b^2, ab), then filter the ring vertically. Memory stays O(K * width).
  const int ow = w - K + 1;
  std::vector<float> ring(static_cast<std::size_t>(5) * K * ow);
  double sum = 0;
  for (int y = 0; y < h; ++y) {
    float* rows = &ring[static_cast<std::size_t>(y % K) * 5 * ow];
    const float* pa = &ya[static_cast<std::size_t>(y) * w];
    const float* pb = &yb[static_cast<std::size_t>(y) * w];
    for (int x = 0; x < ow; ++x) {
      float m[5] = {};
      for (int k = 0; k < K; ++k) {
        const float u = pa[x + k], v = pb[x + k];
        m[0] += g[k] * u, m[1] += g[k] * v, m[2] += g[k] * u * u, m[3] += g[k] * v * v;
        m[4] += g[k] * u * v;
      }
      for (int q = 0; q < 5; ++q) rows[q * ow + x] = m[q];
    }
    if (y < K - 1) continue;
    for (int x = 0; x < ow; ++x) {
      float m[5] = {};
      for (int k = 0; k < K; ++k) {
        const float* r = &ring[static_cast<std::size_t>((y - K + 1 + k) % K) * 5 * ow];
        for (int q = 0; q < 5; ++q) m[q] += g[k] * r[q * ow + x];
      }
      sum += ssim_of(m[0], m[1], m[2] - m[0] * m[0], m[3] - m[1] * m[1], m[4] - m[0] * m[1]);
    }
  }
  return sum / (double(ow) * (h - K + 1));
}

ImageComparison compare_images(const Image& expected, const Image& actual,
                               const CompareOptions& o) {
  ImageComparison c;
  c.same_size = expected.width == actual.width && expected.height == actual.height;
  if (!c.same_size) return c;
  c.pixels = long(actual.width) * actual.height;
  c.allowed = static_cast<long>(o.max_differing_fraction * double(c.pixels));
  double sq = 0;
  for (long i = 0; i < c.pixels; ++i) {
    const std::uint8_t* a = &actual.rgba[4 * i];
    const std::uint8_t* e = &expected.rgba[4 * i];
    for (int k = 0; k < 3; ++k) {
      const int d = std::abs(int(a[k]) - int(e[k]));
      c.max_channel_difference = std::max(c.max_channel_difference, d);
      sq += double(d) * d;
    }
    c.differing += differs(a, e, o.channel_tolerance);
  }
  c.mse = c.pixels ? sq / (3.0 * double(c.pixels)) : 0;
  c.psnr = psnr_of_mse(c.mse);
  c.ssim = ssim(expected, actual);
  return c;
}

Image diff_image(const Image& expected, const Image& actual, int channel_tolerance) {
  Image d(actual.width, actual.height);
  for (int y = 0; y < actual.height; ++y)
    for (int x = 0; x < actual.width; ++x) {
      const std::uint8_t* a = actual.pixel(x, y);
      const bool bad = x >= expected.width || y >= expected.height ||
                       differs(a, expected.pixel(x, y), channel_tolerance);
      const auto faded = static_cast<std::uint8_t>(192 + (a[0] + a[1] + a[2]) / 12);
      std::uint8_t* o = d.pixel(x, y);
      o[0] = bad ? 255 : faded;
      o[1] = o[2] = bad ? 0 : faded;
      o[3] = 255;
    }
  return d;
}

void SequenceComparison::add(const ImageComparison& c) {
  same_size &= c.same_size;
  if (!c.same_size) return;
  if (worst_frame < 0 || c.differing_fraction() > worst_fraction) {
    worst_frame = frames;
    worst_fraction = c.differing_fraction();
  }
  all_match &= c.match();
  max_channel_difference = std::max(max_channel_difference, c.max_channel_difference);
  sum_mse += c.mse;
  sum_ssim += c.ssim;
  ++frames;
}

}  // namespace gs::render
