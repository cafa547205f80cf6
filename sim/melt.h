#pragma once
// Dense thermal starts. Random sequential addition stops at max_rsa_density; a denser gas starts
// on a simple cubic (square) lattice with vacancies at random sites and Maxwell velocities, and
// elastic collisions melt it until nothing of the lattice is left: its Bragg peak has fallen to
// the size of a fluid's fluctuations. Then the clock starts at 0. The simple cubic and square
// lattices are mechanically unstable for hard spheres (rows slide along each other), so they melt
// at every density they can hold, where a close-packed lattice would stay a crystal.
#include <cstdint>

#include "sim/config.h"
#include "sim/initial.h"

namespace gs {

// |rho_k|^2 averaged over the D axes, rho_k = (1/N) sum_j exp(i k . x_j) with k = 2 pi side / box
// along the axis: the first Bragg peak of the lattice of `side` sites per side filling the box.
// It is 1 on the lattice, whatever its vacancies, and about S(k) / N in a fluid, with S(k) of
// order 1 to 3 (the fluid's structure factor there); k is a vector of the periodic box, so the
// positions may be wrapped or not.
template <int D>
double lattice_order(const VecArray<D>& x, double box, std::int64_t side);

// The lattice counts as melted once lattice_order is at most this: 20 / N, a fluid's |rho_k|^2
// (a mean of D exponential variables of mean S(k) / N <= 3 / N) exceeds it in about 1 case of
// 100 in 2D and 1 of 10^4 in 3D, which only costs one more round of collisions; and at most 0.05,
// so that a small system must still lose its lattice.
double melted_order(std::int64_t n);

// Elastic collisions per particle between two looks at the order parameter, and the most before
// giving up (UserError). Measured at N = 1e5 (seed 1), N |rho_k|^2 falls from N to 20 after 17
// collisions per particle at packing 0.4, 80 at 0.5 and 140 at 0.52 in 3D (N = 125000), 17 at
// 0.65 and 30 at 0.70 in 2D,
// and then fluctuates about 1. By then the collision rate per particle is Enskog's with the
// Carnahan-Starling contact value to 1% (20.4 and 10.0 per unit time at 0.5 and 0.4 against
// 20.3 and 10.0), and the cell crossings per collision have levelled off (0.12 and 0.23): the
// Bragg peak is the last of these to relax, so it is the one to wait for.
inline constexpr std::int64_t kMeltCheckCollisions = 10;
inline constexpr std::int64_t kMeltMaxCollisions = 2000;

struct MeltReport {
  std::int64_t collisions = 0;  // elastic collisions spent melting
  double time = 0;              // simulation time they took
  double order = 0;             // lattice_order when melted
};

// The thermal start of `c` above max_rsa_density: the lattice of cubic_lattice (from the
// positions stream) and thermal_velocities (from the velocities stream), melted at restitution 1
// whatever c.restitution, wrapped into the box, with zero total momentum and the temperature
// exactly c.temperature again (collisions keep both only to rounding).
template <int D>
InitialState<D> melted_lattice(const PhysicsConfig& c, MeltReport* report = nullptr);

}  // namespace gs
