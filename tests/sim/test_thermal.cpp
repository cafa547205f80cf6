// Equilibrium and cooling of a homogeneous gas against kinetic theory.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/engine.h"
#include "sim/initial.h"
#include "sim/recorder.h"
#include "tests/sim/thermal_config.h"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;

// Packing fraction of unit-diameter discs or spheres at number density n.
double packing(int dim, double n) {
  return dim == 2 ? kPi * n / 4 : kPi * n / 6;
}

// Contact value of the pair correlation from the equation of state: Henderson (Mol. Phys. 30,
// 971, 1975) in 2D, Carnahan-Starling (J. Chem. Phys. 51, 635, 1969) in 3D.
double contact_g(int dim, double eta) {
  return dim == 2 ? (1 - 7 * eta / 16) / ((1 - eta) * (1 - eta))
                  : (1 - eta / 2) / std::pow(1 - eta, 3);
}

// Z = P / (n T) = 1 + 2 eta g (2D) or 1 + 4 eta g (3D).
double compressibility(int dim, double eta) {
  return 1 + (dim == 2 ? 2 : 4) * eta * contact_g(dim, eta);
}

// Enskog collision frequency per particle: n sigma^(d-1) S g sqrt(pi T / m), with
// S = 2 in 2D and 4 in 3D (Chapman & Cowling; Brilliantov & Poeschel, "Kinetic theory of
// granular gases", ch. 6).
double enskog_rate(int dim, double n, double temperature) {
  return (dim == 2 ? 2 : 4) * n * contact_g(dim, packing(dim, n)) * std::sqrt(kPi * temperature);
}

using test::thermal;

// Elastic gas at n = 0.25: equilibrate for ~30 collisions per particle (the RSA start has no
// equilibrium structure), then average the virial pressure and collision rate over ~300 more.
void check_equation_of_state(int dim) {
  PhysicsConfig c = thermal(dim, 4000, 1.0);
  c.t_max = 300;
  auto sim = make_simulation(c);
  Recorder rec(c);
  sim->run_until(30);
  rec.row(*sim);  // starts the averaging interval here
  sim->run_until(c.t_max);
  const auto row = rec.row(*sim);
  const auto col = [&](const char* name) {
    for (std::size_t k = 0; k < rec.columns().size(); ++k)
      if (rec.columns()[k] == name) return row[k];
    ADD_FAILURE() << "no column " << name;
    return 0.0;
  };
  const double temperature = 2 * col("energy") / (dim * c.particles);
  const double z = col("pressure") / (c.density * temperature);
  const double eta = packing(dim, c.density);
  // The published equations of state are accurate to ~0.1% at this density; 1.5% leaves room for
  // the statistical error of ~3e5 collisions (~0.3% on Z - 1) and finite-size effects at N = 4000.
  EXPECT_NEAR(z / compressibility(dim, eta), 1.0, 0.015) << "Z = " << z;
  // Enskog's rate neglects velocity correlations, which at packing 0.13-0.2 change the collision
  // rate by well under 1% (Alder, Gass & Wainwright 1970); 2% is the bound.
  EXPECT_NEAR(col("collision_rate") / enskog_rate(dim, c.density, temperature), 1.0, 0.02)
      << "rate = " << col("collision_rate");
}

TEST(Thermal, HendersonEquationOfState2D) {
  check_equation_of_state(2);
}
TEST(Thermal, CarnahanStarlingEquationOfState3D) {
  check_equation_of_state(3);
}

// Haff's law: dT/dt = -(1 - r^2) omega_E(T) T / d, with omega_E ~ sqrt(T), integrates to
// T(t) = T0 / (1 + t / tau)^2 with 1 / tau = (1 - r^2) omega_E(T0) / (2 d). The loss per
// collision is (1 - r^2) w^2 / 4 and a Maxwellian gives <w^2> = 4T over collisions. Returns the
// fitted time constant over Enskog's for one realisation.
double haff_time_over_enskog(std::uint64_t realisation) {
  const int dim = 3;
  PhysicsConfig c = thermal(dim, 4000, 0.9);
  c.realisation = realisation;
  // Start from an equilibrated elastic gas so that the pair structure at contact is right.
  PhysicsConfig elastic = c;
  elastic.restitution = 1.0;
  auto warm = make_simulation(elastic);
  warm->run_until(20);
  const Snapshot snap = warm->snapshot();
  InitialState<dim> init;
  for (std::size_t i = 0; i < snap.size(); ++i) {
    Vec<dim> x = snap.position[i].head<dim>();
    for (int k = 0; k < dim; ++k) x[k] -= c.box() * std::floor(x[k] / c.box());
    init.position.push_back(x);
    init.velocity.push_back(snap.velocity[i].head<dim>());
  }
  Engine<dim> sim(c, std::move(init));
  const double t0_temp = 2 * sim.sample().energy / (dim * c.particles);
  const double tau =
      2.0 * dim / ((1 - c.restitution * c.restitution) * enskog_rate(dim, c.density, t0_temp));
  // Fit 1/sqrt(T) = (1 + t / tau) / sqrt(T0) by least squares up to t = tau (T falls fourfold,
  // well before the shearing instability of a box of side 25 sets in for r = 0.9).
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (double t = 0; t <= tau * (1 + 1e-9); t += tau / 20, ++m) {
    sim.run_until(t);
    const double y = 1 / std::sqrt(2 * sim.sample().energy / (dim * c.particles));
    sx += t, sy += y, sxx += t * t, sxy += t * y;
  }
  const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  return 1 / (slope * std::sqrt(t0_temp)) / tau;
}

TEST(Thermal, HaffLawWithEnskogTime) {
  constexpr int kRealisations = 8;
  double sum = 0;
  for (int k = 0; k < kRealisations; ++k) sum += haff_time_over_enskog(k);
  const double mean = sum / kRealisations;
  // 3%: one realisation gives 1.02 with a spread of 0.01 (24 realisations), so the mean of 8 is
  // known to 0.35%. The excess over Enskog grows with the fitting window (0.8% up to tau / 4) and
  // not with N (the same at N = 1000): correlations build up as the gas cools, which Enskog's
  // theory neglects; the cooling state's non-Gaussian a2 (~ -0.015 at r = 0.9, van Noije & Ernst
  // 1998) adds < 0.5%.
  EXPECT_NEAR(mean, 1.0, 0.03) << "tau / tau_Enskog = " << mean;
}

}  // namespace
}  // namespace gs
