#pragma once
// A normalised histogram as a plain struct: the one shape in which P(R,t), P(v,t) and the band
// packing distribution leave sim/, are averaged over realisations and are plotted.
#include <cstdint>
#include <span>
#include <vector>

namespace gs {

struct Histogram {
  std::vector<double> edges;   // bins + 1 increasing bin edges
  std::vector<double> values;  // probability density: count / (samples * width)
  std::uint64_t samples = 0;   // every sample offered, including those outside the edges
  std::uint64_t outside = 0;   // samples outside [edges.front(), edges.back()]

  std::size_t bins() const { return values.size(); }
  double width(std::size_t i) const { return edges[i + 1] - edges[i]; }
  double centre(std::size_t i) const { return 0.5 * (edges[i] + edges[i + 1]); }
  // Sum of value * width: 1 when no sample fell outside, else the fraction inside.
  double integral() const;
};

// Uniform bins on [lo, hi]. With hi <= lo the range is [0, max sample]: every sample is then
// inside, which is what the distributions of distances and speeds want.
struct Binning {
  int bins = 50;
  double lo = 0;
  double hi = 0;
};

// Throws UserError if binning.bins < 1. A sample equal to hi goes into the last bin.
Histogram make_histogram(std::span<const double> samples, const Binning& binning);
// The two steps of make_histogram for a caller that sums other quantities in the same bins
// (radial profiles): the edges it would give these samples, and the bin of a sample x within
// [edges.front(), edges.back()] (one division, the edges the truth near a boundary).
std::vector<double> histogram_edges(std::span<const double> samples, const Binning& binning);
inline std::size_t bin_of(const std::vector<double>& edges, double x) {
  const std::size_t n = edges.size() - 1;
  const double lo = edges.front(), hi = edges.back();
  // A signed conversion: one instruction where an unsigned one takes a dozen (x >= lo here).
  auto i = static_cast<std::size_t>(static_cast<std::int64_t>((x - lo) / (hi - lo) * double(n)));
  i = i < n - 1 ? i : n - 1;
  // The division can land one bin off near an edge; the edges are the truth.
  while (i > 0 && x < edges[i]) --i;
  while (i + 1 < n && x >= edges[i + 1]) ++i;
  return i;
}

// The same distribution in the variable x' = factor * x: edges times factor, densities divided by
// it, so the integral is unchanged. Used for the paper's collapses, e.g. factor = t^-alpha for
// P(R,t) = t^-alpha f1(R t^-alpha) (Eqs. 9 and 10 of the paper).
Histogram rescaled(const Histogram& h, double factor);

}  // namespace gs
