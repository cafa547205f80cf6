#pragma once
// Initial states: where the particles sit (random sequential addition, or a 1D lattice) and how
// they move (all at rest but one kicked particle, or a Maxwell gas).
#include <cstdint>

#include "sim/config.h"
#include "sim/rng.h"
#include "sim/vec.h"

namespace gs {

template <int D>
struct InitialState {
  VecArray<D> position;  // in [0, L)^D; in 1D sorted along the line
  // Empty for a kick, where every particle is at rest but `kicked` (a kick's zeros would cost
  // the start of a 2e7-sphere box 480 MB).
  VecArray<D> velocity;
  std::int32_t kicked = -1;  // the kicked particle, or -1 for a thermal start
  Vec<D> kick_velocity = Vec<D>::Zero();

  Vec<D> velocity_of(std::size_t i) const {
    if (!velocity.empty()) return velocity[i];
    return static_cast<std::int32_t>(i) == kicked ? kick_velocity : Vec<D>::Zero();
  }
};

// Random sequential addition of n unit-diameter spheres in a periodic box of side L: each new
// centre is uniform in the box and kept if it overlaps no earlier sphere. A cell grid makes each
// trial O(1). Throws UserError if the box is too full to finish.
template <int D>
VecArray<D> random_sequential_addition(std::int64_t n, double box, Rng& rng);

// Maxwell velocities at `temperature` (unit mass), total momentum removed, then rescaled so that
// sum v^2 / (d n) equals the temperature exactly.
template <int D>
VecArray<D> thermal_velocities(std::int64_t n, double temperature, Rng& rng);

// n sites of the simple cubic (square) lattice of lattice_side(n, D) sites per side filling the
// box, the empty sites drawn at random so that the vacancies are spread through the box (the first
// n sites would leave a slab of vacuum). The start of dense thermal gases (sim/melt.h); sites are
// returned in lattice order. GS_CHECKs that the spacing is at least a diameter.
template <int D>
VecArray<D> cubic_lattice(std::int64_t n, double box, Rng& rng);

// The direction of a kick: uniform on the unit sphere (in 1D, left or right).
template <int D>
Vec<D> random_direction(Rng& rng);

template <int D>
InitialState<D> make_initial_state(const PhysicsConfig& c);

}  // namespace gs
