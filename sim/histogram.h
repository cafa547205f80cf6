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

// The same distribution in the variable x' = factor * x: edges times factor, densities divided by
// it, so the integral is unchanged. Used for the paper's collapses, e.g. factor = t^-alpha for
// P(R,t) = t^-alpha f1(R t^-alpha) (Eqs. 9 and 10 of the paper).
Histogram rescaled(const Histogram& h, double factor);

}  // namespace gs
