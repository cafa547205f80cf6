// Equilibrium and cooling of a homogeneous gas against kinetic theory.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "analysis/shock.h"
#include "sim/engine.h"
#include "sim/initial.h"
#include "sim/recorder.h"
#include "tests/sim/thermal_config.h"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;

// Contact value of the pair correlation from the equation of state Z = 1 + 2 eta g (2D) or
// 1 + 4 eta g (3D): Henderson (Mol. Phys. 30, 971, 1975) in 2D, Carnahan-Starling (J. Chem.
// Phys. 51, 635, 1969) in 3D (analysis/shock.h).
double contact_g(int dim, double eta) {
  return (hard_sphere_compressibility(dim, eta) - 1) / ((dim == 2 ? 2 : 4) * eta);
}

// Enskog collision frequency per particle: n sigma^(d-1) S g sqrt(pi T / m), with
// S = 2 in 2D and 4 in 3D (Chapman & Cowling; Brilliantov & Poeschel, "Kinetic theory of
// granular gases", ch. 6).
double enskog_rate(int dim, double n, double temperature) {
  return (dim == 2 ? 2 : 4) * n * contact_g(dim, packing_fraction(dim, n)) *
         std::sqrt(kPi * temperature);
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
  const double eta = packing_fraction(dim, c.density);
  // The published equations of state are accurate to ~0.1% at this density; 1.5% leaves room for
  // the statistical error of ~3e5 collisions (~0.3% on Z - 1) and finite-size effects at N = 4000.
  EXPECT_NEAR(z / hard_sphere_compressibility(dim, eta), 1.0, 0.015) << "Z = " << z;
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

// A cooling gas at r = 0.9 started from an equilibrated elastic one, so that the pair structure
// at contact is right, and the Haff time tau of its initial temperature: Haff's law
// dT/dt = -(1 - r^2) omega_E(T) T / d, with omega_E ~ sqrt(T), integrates to
// T(t) = T0 / (1 + t / tau)^2 with 1 / tau = (1 - r^2) omega_E(T0) / (2 d). The loss per
// collision is (1 - r^2) w^2 / 4 and a Maxwellian gives <w^2> = 4T over collisions.
template <int dim>
struct CoolingGas {
  std::unique_ptr<Engine<dim>> sim;
  double t0_temp = 0, tau = 0;
  double temperature() const { return 2 * sim->sample().energy / (dim * sim->config().particles); }
};

template <int dim>
CoolingGas<dim> cooling_gas(std::uint64_t realisation, std::int64_t particles = 4000) {
  PhysicsConfig c = thermal(dim, particles, 0.9);
  c.realisation = realisation;
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
  CoolingGas<dim> g;
  g.sim = std::make_unique<Engine<dim>>(c, std::move(init));
  g.t0_temp = g.temperature();
  g.tau =
      2.0 * dim / ((1 - c.restitution * c.restitution) * enskog_rate(dim, c.density, g.t0_temp));
  return g;
}

// The fitted time constant over Enskog's for one 3D realisation: 1/sqrt(T) = (1 + t / tau) /
// sqrt(T0) by least squares up to t = tau (T falls fourfold, well before the shearing
// instability of a box of side 25 sets in for r = 0.9).
double haff_time_over_enskog(std::uint64_t realisation) {
  auto g = cooling_gas<3>(realisation);
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (double t = 0; t <= g.tau * (1 + 1e-9); t += g.tau / 20, ++m) {
    g.sim->run_until(t);
    const double y = 1 / std::sqrt(g.temperature());
    sx += t, sy += y, sxx += t * t, sxy += t * y;
  }
  const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  return 1 / (slope * std::sqrt(g.t0_temp)) / g.tau;
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
  // 1998) adds < 0.5%. Haff's law where it holds is tested below, in 2D and 3D.
  EXPECT_NEAR(mean, 1.0, 0.03) << "tau / tau_Enskog = " << mean;
}

// Where Haff's law holds, t <= tau / 4 (T falls by 36%): E / E_Haff at tau / 4, and the energy lost
// per collision over (1 - r^2) T, each the mean over realisations. Later the gas cools more
// slowly than Haff's law: velocity correlations build up (the loss per collision falls to ~0.97
// of (1 - r^2) T by t ~ tau in 2D, as Kawahara and Nakanishi also found), which the 3D fit up to
// tau above absorbs into its 3% bound.
template <int dim>
void check_haff_early(int realisations) {
  double energy_ratio = 0, lost = 0, expected = 0;
  for (int k = 0; k < realisations; ++k) {
    auto g = cooling_gas<dim>(std::uint64_t(k));
    double t_prev = 0, temp_prev = g.t0_temp;
    auto coll_prev = g.sim->sample().collisions;
    for (int step = 1; step <= 20; ++step) {
      const double t = g.tau / 4 * step / 20;
      g.sim->run_until(t);
      const double temp = g.temperature();
      const auto coll = g.sim->sample().collisions;
      // Per step of tau / 80 the temperature falls by ~2.5%: its mean over the step is the
      // midpoint value to ~1e-4.
      lost += (temp_prev - temp) * dim * double(g.sim->config().particles) / 2;
      const double r = g.sim->config().restitution;
      expected += (1 - r * r) * 0.5 * (temp + temp_prev) * double(coll - coll_prev);
      temp_prev = temp;
      coll_prev = coll;
      t_prev = t;
    }
    energy_ratio += temp_prev / (g.t0_temp / std::pow(1 + t_prev / g.tau, 2));
  }
  energy_ratio /= realisations;
  // 1.5%: the bound where Haff's law holds; measured 1.001 (2D) and 1.005 (3D) with
  // these seeds, the excess being where correlations begin (see above); the statistical error
  // of the mean energy of 8 x 4000 particles is ~0.3%.
  EXPECT_NEAR(energy_ratio, 1.0, 0.015) << "E / E_Haff at tau / 4, d = " << dim;
  // 1%: ~5e4 collisions over 8 realisations give the mean loss per collision to ~0.5% (the
  // normal relative speed squared has a relative spread ~1 over collisions); molecular chaos
  // makes the ratio exactly 1 at the start and correlations lower it slightly by tau / 4
  // (measured 0.993 in 2D, 0.996 in 3D).
  EXPECT_NEAR(lost / expected, 1.0, 0.01) << "loss per collision / (1 - r^2) T, d = " << dim;
}

TEST(Thermal, HaffLawWhereItHolds2D) {
  check_haff_early<2>(8);
}
TEST(Thermal, HaffLawWhereItHolds3D) {
  check_haff_early<3>(8);
}

}  // namespace
}  // namespace gs
