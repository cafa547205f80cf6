#pragma once
// Power-law exponents of N_t, E_t, R_t against t (the paper's Eqs. 2-4: N_t ~ t^(alpha d),
// E_t ~ t^(alpha d + 2 alpha - 2), R_t ~ t^alpha): a straight-line fit of ln y against ln t over
// a scaling window, the window given or found from the local slope, and a confidence interval
// from bootstrapping over realisations.
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace gs {

// Least-squares line y = intercept + slope x with the usual standard error of the slope
// (independent residuals). Needs >= 3 points with distinct x; UserError otherwise.
struct Line {
  double slope = std::numeric_limits<double>::quiet_NaN();
  double intercept = std::numeric_limits<double>::quiet_NaN();
  double slope_error = std::numeric_limits<double>::quiet_NaN();
  std::size_t points = 0;
};
Line fit_line(std::span<const double> x, std::span<const double> y);

// A closed range of times [t_lo, t_hi].
struct Window {
  double t_lo = 0;
  double t_hi = 0;
};

struct PowerLawFit {
  double exponent = std::numeric_limits<double>::quiet_NaN();
  double prefactor = std::numeric_limits<double>::quiet_NaN();  // y ~ prefactor t^exponent
  Window window;
  std::size_t points = 0;
  // Least-squares standard error of the exponent. Points of a time series are correlated, so it
  // underestimates the uncertainty; the bootstrap interval below is the one to quote.
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  double ci_lo = std::numeric_limits<double>::quiet_NaN();  // bootstrap percentile interval
  double ci_hi = std::numeric_limits<double>::quiet_NaN();
  double confidence = 0;  // of [ci_lo, ci_hi]; 0 when no bootstrap was made
  int resamples = 0;
};

// Local logarithmic slope d ln y / d ln t at each point: the least-squares slope of ln y against
// ln t over the points within half_width_decades of it (at least its two neighbours), which
// smooths the noise of a sampled series. NaN where t <= 0 or y <= 0 in that neighbourhood.
std::vector<double> local_slope(std::span<const double> t, std::span<const double> y,
                                double half_width_decades = 0.1);

// The automatic scaling window: the longest range of times (in ln t) over which the local slope
// stays within a band of full width 2 * tolerance, i.e. max - min <= 2 tolerance.
struct AutoWindowOptions {
  double tolerance = 0.05;          // in units of the exponent
  double half_width_decades = 0.1;  // smoothing of the local slope
  double min_decades = 0.5;         // shorter windows are no scaling regime: UserError
  double t_min = 0;                 // only times in [t_min, t_max] are considered
  double t_max = std::numeric_limits<double>::infinity();
};
Window auto_window(std::span<const double> t, std::span<const double> y,
                   const AutoWindowOptions& options = {});

// Fit of one curve over `window`. UserError (naming the scaling window) if the window is empty,
// reaches outside the data, holds fewer than 3 points or a y <= 0.
PowerLawFit fit_power_law(std::span<const double> t, std::span<const double> y,
                          const Window& window);

// The prefactor of y = prefactor t^exponent with the exponent given (a theory's), by least squares
// of ln y over `window`: ln prefactor = mean(ln y - exponent ln t). No standard error. The same
// UserErrors as fit_power_law.
PowerLawFit fit_power_law_fixed(std::span<const double> t, std::span<const double> y,
                                const Window& window, double exponent);

struct BootstrapOptions {
  int resamples = 1000;
  double confidence = 0.95;
  std::uint64_t seed = 1;  // master seed of the ensemble
  std::uint64_t key = 0;   // distinguishes the quantities fitted from one ensemble (N, E, R ...)
};

// The exponent of the ensemble mean of `realisations` (each a curve on the grid t), with a
// percentile confidence interval from resampling realisations with replacement (gs::Rng,
// Stream::Bootstrap, keyed by seed and key): each resample's mean curve is fitted over the same
// window. UserError if fewer than 2 realisations or a curve's length differs from t.
PowerLawFit fit_power_law_bootstrap(std::span<const double> t,
                                    std::span<const std::vector<double>> realisations,
                                    const Window& window, const BootstrapOptions& options = {});

}  // namespace gs
