#pragma once
// The inset profile across the band: number density of the active particles and their mean
// (scaled) speed against distance from their centre of mass, from sim/observables' radial
// profile. Computed from every active particle, so a 3D slab picture shows the whole shell's
// profile.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "sim/snapshot.h"

namespace gs::render {

struct InsetData {
  std::vector<double> r;        // shell centres, diameters from the centre of mass
  std::vector<double> density;  // active particles per unit area (2D) or volume (3D)
  std::vector<double> speed;    // mean speed over v_rms (or plain when v_rms = 0); NaN if empty
  double r_max = 0;             // outer edge of the last shell
  bool scaled = false;          // speed is over v_rms
};

// From the active particles' positions and speeds (over v_rms when `scaled`), as build_scene
// copies them while it draws them. Empty (no shells) without particles.
InsetData inset_profile(int dim, std::span<const Eigen::Vector3d> positions,
                        std::span<const double> speeds, bool scaled, int bins = 40);
// `band`: the active particles alone (sim/observables' active_subset), with velocities; v_rms > 0
// scales the speeds, dividing each as render/field.h's scaled speed does.
InsetData inset_profile(const Snapshot& band, double v_rms, int bins = 40);

}  // namespace gs::render
