#pragma once
// The hot core behind the band, which decides between the two snowplows (analysis/snowplow.h):
// in the paper's momentum-conserving snowplow the interior is cold and the band carries the
// momentum, so the core's share of the kinetic energy falls to 0; in the pressure-driven one
// (Barbier, Villamaina and Trizac, Phys. Rev. Lett. 2015; J. Stat. Phys. 2016) a hot, dilute
// core keeps a finite share and its pressure pushes the shell.
//  - The core: the active particles closer to their centre of mass than the band's inner edge
//    (analysis/band_measures.h ShellFront::inner_radius: inward from the densest shell, where
//    the active density first falls below half the ambient). Its share is its kinetic energy
//    over that of every active particle, both in the centre-of-mass frame (the kick's drift
//    ~ v0 / N_t taken out, as for P_r).
//  - The kinetic pressure in shells of rho / R_front: p = (1 / (d V_shell)) sum |v - u(rho)|^2
//    (unit masses), u the shell's mean velocity, radial by symmetry (u = V + <(v - V).r> r),
//    so the sum is sum |v - V|^2 - n <(v - V).r>^2. This is the granular-temperature pressure
//    n T of an ideal gas; the hard-core collisional part (n T (Z - 1), analysis/shock.h) is
//    left out, which understates the dense band's pressure, not the dilute core's. Subtracting
//    the shell's own mean takes one degree of freedom of n d: a bias of -1/(n d) per shell.
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "sim/histogram.h"
#include "sim/snapshot.h"

namespace gs {

struct CoreEnergy {
  double front = std::numeric_limits<double>::quiet_NaN();  // ShellFront::radius
  double inner = std::numeric_limits<double>::quiet_NaN();  // ShellFront::inner_radius
  std::size_t core_count = 0;                               // active particles below `inner`
  double core_energy = 0, total_energy = 0;                 // centre-of-mass frame
  double share = std::numeric_limits<double>::quiet_NaN();  // NaN without a band or energy
};

// Of the active particles of `s` (unwrapped positions, velocities needed); `ambient`: number
// density of the gas at rest; `shell`: the width of the front's shells (band_measures.h).
CoreEnergy core_energy(const Snapshot& s, double ambient, double shell = 2);

// The kinetic pressure against x = rho / front_radius on `binning` (of x); 0 in empty shells,
// every shell 0 when front_radius is not positive and finite.
struct PressureProfile {
  std::vector<double> edges;  // of x
  std::vector<double> pressure;
  std::vector<std::size_t> count;
};
PressureProfile kinetic_pressure(const Snapshot& s, double front_radius, const Binning& binning);

// The ensemble's core share between two sample times: its local slope d ln share / d ln t from
// the means at the sample nearest t_from and the last sample at or before t_to, with sigma from
// their standard errors as if independent (they are positively correlated through shared
// realisations, so this overstates it), and what it says: "falls" (slope below 0 by more than
// 2 sigma: the momentum-conserving snowplow's cold interior), "flat" (within 2 sigma of 0: as a
// core that keeps a finite share, the pressure-driven one, would be; as decisive as sigma is
// small), "rises", "not measured" when either mean is NaN (no band yet) and "no core" when
// either is 0.
struct CoreShareTrend {
  double t_from = std::numeric_limits<double>::quiet_NaN();
  double t_to = std::numeric_limits<double>::quiet_NaN();
  double from = std::numeric_limits<double>::quiet_NaN(), from_sem = from;
  double to = std::numeric_limits<double>::quiet_NaN(), to_sem = to;
  double slope = std::numeric_limits<double>::quiet_NaN();
  double sigma = std::numeric_limits<double>::quiet_NaN();
  std::string reading;
};
CoreShareTrend core_share_trend(std::span<const double> t, std::span<const double> mean,
                                std::span<const double> sem, double t_from, double t_to);

}  // namespace gs
