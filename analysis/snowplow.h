#pragma once
// Is the band a momentum-conserving or a pressure-driven snowplow? The paper's alpha = 1/(d+1)
// rests on the band's radial momentum being conserved (P_r constant); a hot core that keeps
// pushing the shell (the pressure-driven snowplow of Barbier, Villamaina and Trizac, "Blast
// dynamics in a dissipative gas", Phys. Rev. Lett. 2015, with an adiabatic core) gives alpha =
// 2/(d+4): 2/7 against 1/4 in 3D, the same 1/3 in 2D. Each picture predicts the exponents of R_t, N_t, E_t and P_r
// (analysis/ensemble_fits.h exponent_from_alpha); the measured exponents weigh them by their
// z-scores, as the phi1 weighing does (analysis/paper.h).
#include <limits>
#include <string>
#include <vector>

#include "analysis/ensemble_fits.h"

namespace gs {

// alpha of the two pictures in d dimensions.
inline double momentum_conserving_alpha(int d) { return 1.0 / (d + 1); }
inline double pressure_driven_alpha(int d) { return 2.0 / (d + 4); }

struct SnowplowReading {
  Quantity quantity = Quantity::RadiusRms;
  double exponent = std::numeric_limits<double>::quiet_NaN();
  double sigma = std::numeric_limits<double>::quiet_NaN();  // stat and window systematic
  double z_momentum = std::numeric_limits<double>::quiet_NaN();
  double z_pressure = std::numeric_limits<double>::quiet_NaN();
};

// The readings of R_t, N_t, E_t and P_r of one r < 1 ensemble, and which picture they favour:
// chi^2 = sum of z^2 over the readings with a plateau against each picture; the odds are the
// likelihood ratio exp((chi2_other - chi2_near) / 2), in Kass and Raftery's words (as for phi1);
// "neither" when the nearer picture's chi^2 exceeds its 99.7% quantile for that many readings
// (the data exclude it as a 3 sigma deviation would); "no readings" without any plateau; in 2D,
// where both pictures give 1/3, "both (the same alpha in 2D)".
struct SnowplowVerdict {
  int d = 0;
  std::vector<SnowplowReading> readings;
  std::size_t used = 0;  // readings with a plateau
  double chi2_momentum = std::numeric_limits<double>::quiet_NaN();
  double chi2_pressure = std::numeric_limits<double>::quiet_NaN();
  double odds = std::numeric_limits<double>::quiet_NaN();
  std::string favoured;  // "momentum-conserving", "pressure-driven", "neither", ...
  std::string strength;
};
SnowplowVerdict weigh_snowplow(int d, const EnsembleFits& fits);

// Where the runs end, which needs no plateau. A snowplow is a shell of the swept mass N ~ R^d
// whose momentum grows as t^epsilon; then alpha = (1 + epsilon) / (d + 1). The
// momentum-conserving snowplow is epsilon = 0, the pressure-driven one epsilon = (d - 2) / (d + 4)
// (1/7 in 3D, 0 in 2D). Two readings of epsilon at a run's end (EndSlope, the last decade):
//  - P_r's own slope, whose drift says which picture the run is heading to:
//    - a significant drift (beyond 2 sigma + 0.001, the plateau rule's floor) heads towards the
//      pictures whose epsilon lies on its side: the one ("momentum-conserving",
//      "pressure-driven") when the other lies behind, "undecided" when both lie ahead (the slope
//      reaches the nearer first, and whether it stops there is not seen), "neither" when none
//      does;
//    - no significant drift: the picture within 3 sigma + 0.001 of the slope, "neither" when
//      both are beyond, "undecided" when both are within;
//    - in 2D, where both give 0, "both (the same alpha in 2D)"; "no readings" when P_r's last
//      decade has no usable slope;
//  - the shell's momentum N_t dR_t/dt, slope x_N + x_R - 1, with its z against each picture: the
//    snowplow's own kinematics, blind to how the band's particles share their radial speeds
//    (sigma: the two end slopes' errors as if independent, and the floor, in quadrature).
struct SnowplowEnd {
  int d = 0;
  EndSlope epsilon;                                         // P_r's
  EndSlope radius, count, energy;                           // R_t, N_t, E_t
  double shell = std::numeric_limits<double>::quiet_NaN();  // x_N + x_R - 1
  double shell_sigma = std::numeric_limits<double>::quiet_NaN();
  double shell_z_momentum = std::numeric_limits<double>::quiet_NaN();
  double shell_z_pressure = std::numeric_limits<double>::quiet_NaN();
  std::string heading;
};
SnowplowEnd snowplow_at_the_end(int d, const EnsembleFits& fits);

}  // namespace gs
