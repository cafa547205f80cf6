#include "sim/histogram.h"

#include <algorithm>
#include <cmath>

#include "sim/error.h"

namespace gs {

double Histogram::integral() const {
  double sum = 0;
  for (std::size_t i = 0; i < bins(); ++i) sum += values[i] * width(i);
  return sum;
}

Histogram make_histogram(std::span<const double> samples, const Binning& binning) {
  if (binning.bins < 1) throw UserError("histogram bins must be at least 1");
  double lo = binning.lo, hi = binning.hi;
  if (!(hi > lo)) {
    lo = 0;
    hi = 0;
    for (double x : samples) hi = std::max(hi, x);
    if (!(hi > lo)) hi = lo + 1;  // all samples at 0 (or none): any positive range holds them
  }
  Histogram h;
  const auto n = static_cast<std::size_t>(binning.bins);
  h.edges.resize(n + 1);
  for (std::size_t i = 0; i <= n; ++i) h.edges[i] = lo + (hi - lo) * double(i) / double(n);
  h.edges[n] = hi;  // exact upper edge, so "x == hi goes in the last bin" holds bit for bit
  std::vector<std::uint64_t> count(n, 0);
  for (double x : samples) {
    ++h.samples;
    if (!(x >= lo && x <= hi)) {
      ++h.outside;
      continue;
    }
    auto i = static_cast<std::size_t>((x - lo) / (hi - lo) * double(n));
    i = std::min(i, n - 1);
    // The division can land one bin off near an edge; the edges are the truth.
    while (i > 0 && x < h.edges[i]) --i;
    while (i + 1 < n && x >= h.edges[i + 1]) ++i;
    ++count[i];
  }
  h.values.assign(n, 0.0);
  if (h.samples == 0) return h;
  for (std::size_t i = 0; i < n; ++i)
    h.values[i] = double(count[i]) / (double(h.samples) * h.width(i));
  return h;
}

Histogram rescaled(const Histogram& h, double factor) {
  GS_CHECK_MSG(factor > 0 && std::isfinite(factor), "rescale factor must be positive");
  Histogram s = h;
  for (double& e : s.edges) e *= factor;
  for (double& v : s.values) v /= factor;
  return s;
}

}  // namespace gs
