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

std::vector<double> histogram_edges(std::span<const double> samples, const Binning& binning) {
  if (binning.bins < 1) throw UserError("histogram bins must be at least 1");
  double lo = binning.lo, hi = binning.hi;
  if (!(hi > lo)) {
    lo = 0;
    hi = 0;
    for (double x : samples) hi = std::max(hi, x);
    if (!(hi > lo)) hi = lo + 1;  // all samples at 0 (or none): any positive range holds them
  }
  const auto n = static_cast<std::size_t>(binning.bins);
  std::vector<double> edges(n + 1);
  for (std::size_t i = 0; i <= n; ++i) edges[i] = lo + (hi - lo) * double(i) / double(n);
  edges[n] = hi;  // exact upper edge, so "x == hi goes in the last bin" holds bit for bit
  return edges;
}

Histogram make_histogram(std::span<const double> samples, const Binning& binning) {
  Histogram h;
  h.edges = histogram_edges(samples, binning);
  const std::size_t n = h.edges.size() - 1;
  const double lo = h.edges.front(), hi = h.edges.back();
  std::vector<std::uint64_t> count(n, 0);
  for (double x : samples) {
    ++h.samples;
    if (!(x >= lo && x <= hi)) {
      ++h.outside;
      continue;
    }
    ++count[bin_of(h.edges, x)];
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
