#include "render/image_compare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <vector>

#include <Eigen/Dense>

#include "sim/error.h"

namespace gs::render {
namespace {

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

namespace {

int chebyshev(const std::uint8_t* a, const std::uint8_t* b) {
  return std::max({std::abs(int(a[0]) - int(b[0])), std::abs(int(a[1]) - int(b[1])),
                   std::abs(int(a[2]) - int(b[2]))});
}

// Largest channel difference between x and the point of the convex hull of v[0..n) nearest to
// x (in RGB, Euclidean): how far x is from every blend of those colours. The nearest point is
// the projection on the affine hull of one of the subsets of v (a vertex, an edge, a face or
// the whole tetrahedron) that lands inside it; every subset is tried, 15 for n = 4.
float off_hull(const std::uint8_t* x, const std::array<float, 3>* v, int n) {
  float best = 1e9f;
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    int idx[4], k = 0;
    for (int i = 0; i < n; ++i)
      if (mask & (1u << i)) idx[k++] = i;
    const std::array<float, 3>& o = v[idx[0]];
    Eigen::Vector3f r(float(x[0]) - o[0], float(x[1]) - o[1], float(x[2]) - o[2]);
    Eigen::Matrix<float, 3, Eigen::Dynamic> e(3, k - 1);
    for (int j = 1; j < k; ++j)
      for (int c = 0; c < 3; ++c) e(c, j - 1) = v[idx[j]][c] - o[c];
    Eigen::Vector3f residual = r;
    if (k > 1) {
      const Eigen::MatrixXf g = e.transpose() * e;
      Eigen::LDLT<Eigen::MatrixXf> ldlt(g);
      if (ldlt.info() != Eigen::Success || std::abs(g.determinant()) < 1e-3f) continue;
      const Eigen::VectorXf lambda = ldlt.solve(e.transpose() * r);
      if ((lambda.array() < -1e-6f).any() || lambda.sum() > 1 + 1e-6f) continue;
      residual = r - e * lambda;
    }
    best = std::min(best, residual.cwiseAbs().maxCoeff());
  }
  return best;
}


// How far pixel (x, y) of `from` lies from every blend of the same pixel of `to` with its
// neighbours in one quadrant (the pixel, one beside, one above or below, one diagonal): what
// a shift of less than a pixel in that quadrant's direction mixes, rims of several discs
// included. Stops at the first quadrant within `tolerance`.
float unexplained(const Image& from, const Image& to, int x, int y, int tolerance) {
  const std::uint8_t* p = from.pixel(x, y);
  float best = float(chebyshev(p, to.pixel(x, y)));
  for (int sy = -1; sy <= 1 && best > tolerance; sy += 2)
    for (int sx = -1; sx <= 1 && best > tolerance; sx += 2) {
      std::array<float, 3> v[4];
      int n = 0;
      for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
          const int qx = x + sx * dx, qy = y + sy * dy;
          if (qx < 0 || qy < 0 || qx >= to.width || qy >= to.height) continue;
          const std::uint8_t* q = to.pixel(qx, qy);
          for (int k = 0; k < 3; ++k) v[n][k] = float(q[k]);
          ++n;
        }
      best = std::min(best, off_hull(p, v, n));
    }
  return best;
}

// Per pixel, 0 where each picture is explained by the other within the tolerance, else the
// larger of the two unexplained amounts (at least 1).
std::vector<std::uint8_t> excess_map(const Image& e, const Image& a, int tolerance) {
  std::vector<std::uint8_t> m(static_cast<std::size_t>(a.width) * a.height, 0);
  // The outermost rows and columns are left out: what a shift brings in there comes from
  // outside the picture, which neither side has.
  for (int y = 1; y + 1 < a.height; ++y)
    for (int x = 1; x + 1 < a.width; ++x) {
      if (chebyshev(a.pixel(x, y), e.pixel(x, y)) <= tolerance) continue;
      const float u = std::max(unexplained(a, e, x, y, tolerance),
                               unexplained(e, a, x, y, tolerance));
      if (u > tolerance)
        m[static_cast<std::size_t>(y) * a.width + x] =
            static_cast<std::uint8_t>(std::clamp(std::lround(u), 1L, 255L));
    }
  return m;
}

}  // namespace

ImageComparison compare_images(const Image& expected, const Image& actual,
                               const CompareOptions& o) {
  ImageComparison c;
  c.same_size = expected.width == actual.width && expected.height == actual.height;
  if (!c.same_size) return c;
  c.pixels = long(actual.width) * actual.height;
  c.max_pixels = o.max_blob_pixels;
  c.max_mass = o.max_blob_mass;
  double sq = 0;
  for (long i = 0; i < c.pixels; ++i) {
    const std::uint8_t* a = &actual.rgba[4 * i];
    const std::uint8_t* e = &expected.rgba[4 * i];
    for (int k = 0; k < 3; ++k) {
      const int d = std::abs(int(a[k]) - int(e[k]));
      c.max_channel_difference = std::max(c.max_channel_difference, d);
      sq += double(d) * d;
    }
  }
  c.mse = c.pixels ? sq / (3.0 * double(c.pixels)) : 0;
  c.psnr = psnr_of_mse(c.mse);
  c.ssim = ssim(expected, actual);
  if (c.max_channel_difference <= o.channel_tolerance) return c;

  // Blobs: 8-connected groups of differing pixels, by a flood fill with an explicit stack.
  std::vector<std::uint8_t> m = excess_map(expected, actual, o.channel_tolerance);
  const int w = actual.width, h = actual.height;
  std::vector<long> stack;
  std::vector<int> mass_of(m.size(), 0);
  for (long start = 0; start < c.pixels; ++start) {
    if (!m[start]) continue;
    Blob b;
    b.x0 = b.x1 = int(start % w);
    b.y0 = b.y1 = int(start / w);
    stack.assign(1, start);
    b.peak = m[start];
    mass_of[start] = m[start] - o.channel_tolerance;
    m[start] = 0;
    while (!stack.empty()) {
      const long i = stack.back();
      stack.pop_back();
      ++b.pixels;
      b.mass += mass_of[i];
      const int x = int(i % w), y = int(i / w);
      b.x0 = std::min(b.x0, x), b.x1 = std::max(b.x1, x);
      b.y0 = std::min(b.y0, y), b.y1 = std::max(b.y1, y);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const long q = long(qy) * w + qx;
          if (!m[q]) continue;
          b.peak = std::max(b.peak, int(m[q]));
          mass_of[q] = m[q] - o.channel_tolerance;
          m[q] = 0;
          stack.push_back(q);
        }
    }
    c.differing += b.pixels;
    ++c.blobs;
    if (c.blobs == 1 || c.excess_of(b) > c.excess_of(c.largest)) c.largest = b;
  }
  return c;
}

Image diff_image(const Image& expected, const Image& actual, const CompareOptions& o) {
  Image d(actual.width, actual.height);
  const bool same_size = expected.width == actual.width && expected.height == actual.height;
  const std::vector<std::uint8_t> m =
      same_size ? excess_map(expected, actual, o.channel_tolerance) : std::vector<std::uint8_t>{};
  for (int y = 0; y < actual.height; ++y)
    for (int x = 0; x < actual.width; ++x) {
      const std::uint8_t* a = actual.pixel(x, y);
      const bool bad = !same_size || m[static_cast<std::size_t>(y) * actual.width + x] != 0;
      const auto faded = static_cast<std::uint8_t>(192 + (a[0] + a[1] + a[2]) / 12);
      std::uint8_t* p = d.pixel(x, y);
      p[0] = bad ? 255 : faded;
      p[1] = p[2] = bad ? 0 : faded;
      p[3] = 255;
    }
  return d;
}

void SequenceComparison::add(const ImageComparison& c) {
  same_size &= c.same_size;
  if (!c.same_size) return;
  if (worst_frame < 0 || c.excess_of(c.largest) > worst.excess_of(worst.largest)) {
    worst_frame = frames;
    worst = c;
  }
  all_match &= c.match();
  max_channel_difference = std::max(max_channel_difference, c.max_channel_difference);
  sum_mse += c.mse;
  sum_ssim += c.ssim;
  ++frames;
}

}  // namespace gs::render
