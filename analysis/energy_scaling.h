#pragma once
// phi1 read from the energy curves themselves, with no plateau of a local slope, which
// the 3D runs do not reach. If t_c1 ~ (1 - r^2)^-phi1 is the one time scale of the crossover, E_t /
// E_0 = g(t (1 - r^2)^phi1) for r near 1, and two readings follow that do not need the late scaling
// regime the intersection rule (crossover.h) extrapolates from:
//  - the time t_f at which <E_t> first falls to a fixed fraction f of E_0: phi1 = -d ln t_f /
//    d ln(1 - r^2) between two r, the same for every f where the form holds (its level
//    dependence is the test of the form);
//  - the collapse: the phi1 that puts ln(<E_t> / E_0) of two r on one curve against
//    ln t + phi1 ln(1 - r^2), over the part of the curves between two energy fractions.
// Both between neighbouring r, so that the pair nearest r = 1 reads the divergence the paper
// defines. Intervals: 95% percentiles over draws in which each r's realisations are resampled
// with replacement (independent ensembles). The scaling estimate: during the elastic blast
// the energy lost by time t is ~ (1 - r^2) t^(2/(d+2)) (collision rate per particle t^(-d/(d+2))
// times energy per collision t^(-2d/(d+2)) times N_t ~ t^(2d/(d+2))), so a finite fraction is
// lost by t_c1 ~ (1 - r^2)^-((d+2)/2): phi1 = 2 in 2D, 2.5 in 3D.
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace gs {

// One r's energy: the shared time grid, each realisation's E_t on it, E_0 and the control
// 1 - r^2.
struct EnergyCurves {
  double control = 0;
  std::string label;  // "r = 0.9"
  std::vector<double> t;
  std::vector<std::vector<double>> realisations;
  double e0 = 0.5;
  std::vector<double> mean() const;  // over realisations; UserError when there are none
};

// First time `y` (non-increasing in expectation, positive) falls to `level`: linear in ln t and
// ln y between the last sample above and the first at or below; NaN if it never does or starts
// there already.
double time_to_level(std::span<const double> t, std::span<const double> y, double level);

// Mean squared difference of ln y between the two curves where they overlap against
// x = ln t + phi ln control, each curve's samples with y / E_0 in [lo, hi] interpolated on the
// other (both ways); infinity with fewer than 4 matched samples.
double collapse_misfit(const EnergyCurves& a, std::span<const double> mean_a, const EnergyCurves& b,
                       std::span<const double> mean_b, double phi, double lo, double hi);

struct Phi1Options {
  std::vector<double> levels = {0.5, 0.1, 0.01};  // fractions of E_0 for the level reading
  double collapse_lo = 0.01;  // the collapse uses E / E_0 in [collapse_lo, collapse_hi]
  double collapse_hi = 0.5;
  double phi_min = 0, phi_max = 8;  // scanned for the collapse
  int resamples = 200;
  std::uint64_t seed = 1;
};

// One reading between two r: the estimate from the means, its 95% interval (NaN with fewer
// than 10 draws that give one), and why there is none.
struct Phi1Reading {
  std::string from, to;
  double level = std::numeric_limits<double>::quiet_NaN();  // NaN: the collapse
  double phi = std::numeric_limits<double>::quiet_NaN();
  double ci_lo = std::numeric_limits<double>::quiet_NaN();
  double ci_hi = std::numeric_limits<double>::quiet_NaN();
  std::string note;
};

// The time <E_t> of one r first falls to level x E_0 (NaN if it does not within the run), and
// the same in each of o.resamples draws of its realisations with replacement: the crossover
// times whose ratios the level readings are (fig10 of `figures`).
struct FractionTime {
  double t = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> draws;
};
FractionTime time_to_fraction(const EnergyCurves& c, double level, const Phi1Options& o);

Phi1Reading phi1_from_level(const EnergyCurves& a, const EnergyCurves& b, double level,
                            const Phi1Options& o);
Phi1Reading phi1_from_collapse(const EnergyCurves& a, const EnergyCurves& b, const Phi1Options& o);

// For each neighbouring pair of `curves` (in the order given, r ascending): the collapse, then
// one reading per level.
std::vector<Phi1Reading> phi1_readings(const std::vector<EnergyCurves>& curves,
                                       const Phi1Options& o);

// Of `readings` (phi1_readings' order), the one of the kind `level` (NaN: the collapse) from the
// pair nearest r = 1 that gives an estimate; nullptr if no pair does.
const Phi1Reading* nearest_limit_reading(const std::vector<Phi1Reading>& readings, double level);

// The scaling estimate (d + 2) / 2 from cumulative dissipation during the elastic blast.
inline double phi1_scaling_estimate(int d) {
  return (d + 2) / 2.0;
}

}  // namespace gs
