#pragma once
// Measures of the band that do not depend on how a grid cuts it: the paper's "typical
// packing fraction ... 0.78-0.82" in cells of side 10 does not say how cells straddling the
// band's edges count, and a band about one cell thick puts nearly every cell on an edge. So the
// cell reading is kept as a whole distribution and beside it stand:
//  - the densest cell over shifted grids (cells of side ~10 holding active particles, the grid
//    offset by cell/shifts along each axis in turn);
//  - the local packing around each active particle: every particle centre within local_radius
//    of it, as whole-particle volume over the ball's volume (unbiased for a uniform medium; no
//    edge of a grid, only the band's own edges for particles near them), its median and upper
//    quantile over active particles;
//  - the cell reading at other sides (5 and 20), whose trend with the side shows the band-edge
//    dilution: the smaller the cell, the fewer straddle an edge, the higher the mean;
//  - each active particle's own Voronoi cell (2D): its disc's area over the cell's, the median
//    over active particles (the declared reading, docs/definitions.md);
//  - the front radius and the shell's peak number density on shells of fixed width around the
//    active centre of mass (not scaling with t^alpha, so that a radius read off them is not the
//    theory's by construction): the front is where the active density, going outward from the
//    densest shell, first falls below half the ambient density; the peak is that densest shell.
// Positions are wrapped into the periodic box for the packing measures; distances from the
// centre use the snapshot's unwrapped positions.
#include <Eigen/Core>
#include <limits>
#include <span>
#include <vector>

#include "sim/histogram.h"
#include "sim/snapshot.h"

namespace gs {

struct BandMeasureOptions {
  double cell = 10;         // the paper's cell side
  int shifts = 4;           // grid offsets per axis for the densest cell
  double local_radius = 3;  // diameters
  double local_quantile = 0.9;
  double shell = 2;  // width of the shells of the front radius, diameters
  double small_cell = 5, large_cell = 20;  // the cell scan beside the paper's 10
  // Half side of the square a Voronoi cell is clipped to: a particle on the band's inner edge,
  // facing the near-empty core, has a cell bounded by this instead of by the core's few
  // particles. Inside a band (neighbours ~1 apart) the cell reaches ~0.6 and never meets it.
  double voronoi_cap = 2;
};

struct ShellFront {
  double radius = std::numeric_limits<double>::quiet_NaN();
  double peak_density = std::numeric_limits<double>::quiet_NaN();  // number per unit volume
  // The band's inner edge, the same rule going inward: where the active density, going inward
  // from the densest shell, first falls below half the ambient density; 0 when it never does
  // (the band reaches the centre).
  double inner_radius = std::numeric_limits<double>::quiet_NaN();
};

// From distances of active particles to their centre; NaN when the densest shell is below half
// the ambient density (no band yet).
ShellFront shell_front(std::span<const double> distances, int dim, double ambient_density,
                       double shell);

// shell_front of active particles (unwrapped positions) around their centre of mass, given as
// positions (Simulation::active_positions) or as a snapshot.
ShellFront front_of(std::span<const Eigen::Vector3d> active, int dim, double ambient_density,
                    double shell = 2);
ShellFront measure_front(const Snapshot& s, double ambient_density, double shell = 2);

struct BandMeasures {
  double densest_cell = std::numeric_limits<double>::quiet_NaN();
  double local_median = std::numeric_limits<double>::quiet_NaN();
  double local_upper = std::numeric_limits<double>::quiet_NaN();  // options.local_quantile
  // Active-weighted mean cell packing (BandPacking::typical) at cells of small_cell, large_cell.
  double cell_small = std::numeric_limits<double>::quiet_NaN();
  double cell_large = std::numeric_limits<double>::quiet_NaN();
  double voronoi_median = std::numeric_limits<double>::quiet_NaN();  // 2D only
  ShellFront front;
};

// `ambient_density`: number density of the gas at rest. Needs a cubic periodic box (info.cube_side() > 0).
BandMeasures measure_band(const Snapshot& s, double ambient_density,
                          const BandMeasureOptions& options = {});

// Each active particle's disc area over the area of its Voronoi cell among all particles (active
// or at rest; minimum image in the cubic periodic box), the cell clipped to the square of half
// side `cap` around the particle; in the order of the active particles. 2D only (UserError
// otherwise, or without a cubic box). Written for this: half-plane clipping by the bisectors of
// neighbours in order of distance, stopped when the next is beyond twice the cell's farthest
// vertex (no farther one can cut it).
std::vector<double> voronoi_packing(const Snapshot& s, double cap);

// The cell packing fractions as an active-weighted distribution: each cell counts with the number
// of active particles in it (fractions and weights from sim/observables.h BandPacking).
Histogram weighted_cell_histogram(std::span<const double> fraction,
                                  std::span<const std::uint32_t> active, const Binning& binning);

}  // namespace gs
