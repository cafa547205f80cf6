#pragma once
// Observables of the band, computed from a Snapshot of the active particles (Jabeen, Rajesh, Ray,
// EPL 2010): shape (R_t, v_t, gyration tensor, anisotropy A), the distributions P(R,t) and
// P(v,t), the band packing fraction and radial profiles. Positions are the snapshot's unwrapped
// ones, so a band that straddles the periodic boundary is measured in one piece. A snapshot
// without an active column (hand-written) counts every particle as active.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "sim/histogram.h"
#include "sim/rng.h"
#include "sim/snapshot.h"

namespace gs {

struct Shape {
  int dim = 2;
  std::size_t active = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();           // centre of mass (unit masses)
  Eigen::Vector3d centre_velocity = Eigen::Vector3d::Zero();  // zero if no velocities
  double radius_rms = 0;  // R_t = sqrt(trace of the gyration tensor)
  double speed_rms = 0;   // v_t, lab frame; zero if no velocities
  Eigen::Matrix3d gyration =
      Eigen::Matrix3d::Zero();  // (1/N) sum (x - c)(x - c)^T, dim x dim block
  Eigen::Vector3d eigenvalues = Eigen::Vector3d::Zero();  // descending; entries beyond dim are 0
  double anisotropy = 0;                                  // anisotropy_index(dim, eigenvalues)
};

// Throws UserError if the snapshot's dimension is not 1, 2 or 3.
Shape measure_shape(const Snapshot& s);

// A(t) of one configuration, from the gyration eigenvalues (the paper averages it over
// realisations). 2D: ((l1 - l2)/(l1 + l2))^2, the paper's definition. 3D: the relative shape
// anisotropy kappa^2 = 1 - 3 (l1 l2 + l2 l3 + l3 l1)/(l1 + l2 + l3)^2 (Theodorou & Suter,
// Macromolecules 18, 1206 (1985)); both are 0 for a disc or sphere and 1 for a rod, so the 2D and
// 3D indices read the same way. 1D: 0. Defined as 0 when all eigenvalues vanish (fewer than two
// distinct positions), where no shape exists.
double anisotropy_index(int dim, const Eigen::Vector3d& eigenvalues);

// The radial momentum of the active particles (unit masses), P_r = sum (v - V) . (x - c)/|x - c|
// with c and V their centre of mass and its velocity (the kick's net drift ~ v0 / N_t taken out,
// as in RadialProfile). A momentum-conserving snowplow keeps P_r ~ N_t R_t / t constant
// (alpha = 1/(d+1)); a shell pushed by a hot core's pressure gains it. Particles at c count 0;
// 0 without velocities.
double radial_momentum(const Snapshot& s);

// A(t) of the active particles with every direction about their centre of mass redrawn uniformly
// (distances kept), averaged over `shuffles` draws: what an isotropic cloud of the same N and
// radial distribution reads. A of N points is not 0 even when their law is isotropic (~1/N,
// times a factor set by the radial distribution), so A -> 0 is judged against this floor.
double isotropic_anisotropy(const Snapshot& s, Rng& rng, int shuffles = 4);

// E_t: the kinetic energy of every particle (unit masses); 0 for a snapshot without velocities.
double kinetic_energy(const Snapshot& s);

// Volume of a d-dimensional ball of radius a (length in 1D, area in 2D).
double ball_volume(int d, double a);

// The active particles of `s` alone, in their order, with s.info. Every measure but the band
// packing looks at active particles only; at 2e6 spheres they are a few per cent of the snapshot,
// scattered through it, and measuring them from this copy reads the big arrays once instead of
// once per measure.
Snapshot active_subset(const Snapshot& s);

// Distances of active particles from `centre`, and their speeds, in particle order.
std::vector<double> active_distances(const Snapshot& s, const Eigen::Vector3d& centre);
std::vector<double> active_speeds(const Snapshot& s);  // UserError if s has no velocities

// P(R,t): normalised distribution of distances of active particles from their centre of mass.
Histogram radial_distribution(const Snapshot& s, const Binning& binning = {});
// P(v,t): normalised distribution of the speeds of active particles.
Histogram speed_distribution(const Snapshot& s, const Binning& binning = {});
// The scaled forms of the paper's Eqs. (9), (10): x = R t^-alpha with density t^alpha P(R,t), and
// x = v t^(1-alpha) with density t^(alpha-1) P(v,t). UserError unless time > 0.
Histogram scaled_radial_distribution(const Histogram& p_r, double time, double alpha);
Histogram scaled_speed_distribution(const Histogram& p_v, double time, double alpha);

// Band packing fraction as in the paper: space cut into cells of side ~10, the packing fraction
// of each cell (all particles in it, active or not, times the volume of their sphere, over the
// cell volume) is taken for every cell that holds at least one active (band) particle.
struct PackingOptions {
  double cell = 10.0;                             // the paper's cell side
  double upper_quantile = 0.9;                    // for BandPacking::upper
  Binning binning{.bins = 50, .lo = 0, .hi = 1};  // for the distribution of cell fractions
};

struct BandPacking {
  // The definition of `typical`, to be printed next to the number.
  static constexpr const char* definition =
      "mean packing fraction of cells of side ~10 holding band (active) particles, each cell "
      "weighted by its number of active particles";
  double cell_side = 10;         // actual side: the box is cut into a whole number of cells >= cell
  std::vector<double> fraction;  // per band cell, in cell-index order
  std::vector<std::uint32_t> active;  // active particles in that cell
  Histogram distribution;             // of `fraction`, each band cell counted once
  // Cells on the edge of the band are only partly filled; weighting by the active particles
  // they hold makes the typical value that of the cells where the band's particles actually sit.
  double typical = std::numeric_limits<double>::quiet_NaN();
  double mean = std::numeric_limits<double>::quiet_NaN();  // unweighted, over band cells
  double mode = std::numeric_limits<double>::quiet_NaN();  // centre of the fullest bin
  // Active-weighted quantile (options.upper_quantile) of the cell fractions: the packing of the
  // cells the band fills. A band only ~10 diameters thick (2D, N_t ~ 5e3) leaves most cells of
  // side 10 straddling its edges, which pulls `typical` below the packing inside the band;
  // the paper's 0.78-0.82 is to be compared with both.
  double upper = std::numeric_limits<double>::quiet_NaN();
};

// With info.box > 0 the box is cut into n = floor(L / cell) cells per side and positions are
// wrapped into it; with box 0 (hand-written snapshot) cells of side `cell` tile unbounded space.
BandPacking band_packing(const Snapshot& s, const PackingOptions& options = {});

// Profiles of active particles against distance from their centre of mass, in shells.
struct RadialProfile {
  std::vector<double> edges;         // bins + 1 shell radii
  std::vector<std::uint64_t> count;  // active particles per shell
  std::vector<double> density;       // count / shell volume (length in 1D, area in 2D)
  std::vector<double> mean_speed;    // lab-frame |v|; NaN in empty shells
  // v . (x - c)/|x - c| with v taken relative to the centre-of-mass velocity of the active
  // particles: the kick gives the band a net drift ~ v0 / N_t, of the order of v_t itself when
  // v_t R_t^d ~ const (the paper's radial momentum argument), so the lab frame would mix it in.
  std::vector<double> mean_radial_velocity;
  // The sums behind the two means, so that an ensemble can average sum over count (empty shells
  // of one realisation then weigh nothing instead of making the mean NaN).
  std::vector<double> speed_sum, radial_velocity_sum;
};
RadialProfile radial_profile(const Snapshot& s, const Binning& binning = {});
// The shells, counts, density and mean speed of the profile above from the active particles'
// positions and their speeds alone (speeds[i] belongs to positions[i], in any unit; no radial
// velocity): what a movie's inset needs every frame, from the speeds the renderer has already
// read. The same bits as the profile of a snapshot of these particles.
RadialProfile speed_profile(int dim, std::span<const Eigen::Vector3d> positions,
                            std::span<const double> speeds, const Binning& binning = {});

// "Faster particles on the inner edge of the band" as numbers.
struct InnerEdge {
  double correlation =
      std::numeric_limits<double>::quiet_NaN();  // Pearson(speed, R); < 0: faster inside
  double median_radius = std::numeric_limits<double>::quiet_NaN();
  double inner_speed = std::numeric_limits<double>::quiet_NaN();  // mean speed, R < median
  double outer_speed = std::numeric_limits<double>::quiet_NaN();  // mean speed, R >= median
  double ratio = std::numeric_limits<double>::quiet_NaN();  // inner / outer; > 1: faster inside
};
InnerEdge inner_edge_speed(const Snapshot& s);

}  // namespace gs
