#pragma once
// The physics of one run: a plain struct with the paper's values as defaults. The command line
// and TOML files fill it; validate() is the single place that rejects impossible input.
#include <cstdint>
#include <string>

namespace gs {

enum class Initial { Kick, Thermal };
enum class KickSite { Random, Centre };
// Box: the periodic box of N particles. Unbounded: a kick's gas at rest made cell by cell where
// the front arrives (sim/unbounded_medium.h), N then caps the particles made. The commands and
// Python take default_medium() when no medium is given; the struct's own default stays the box,
// the paper's system and what every file written before the medium existed means.
enum class Medium { Box, Unbounded };

struct PhysicsConfig {
  int dim = 2;
  std::int64_t particles = 250000;  // the paper's 2D system
  double density = 0.25;            // number density n (diameter 1)
  double restitution = 0.1;         // r; the paper's Fig. 1(a)
  double cutoff = 1e-4;             // delta: collisions slower than this are elastic
  double speed = 1.0;               // v0 of the kicked particle
  std::uint64_t seed = 1;
  std::uint64_t realisation = 0;  // index within an ensemble; streams are keyed by it
  double t_max = 100000.0;        // paper time 5e4 in 2D: the last time of Fig. 1(a)
  Initial initial = Initial::Kick;
  KickSite kick_site = KickSite::Random;
  double temperature = 1.0;  // thermal initial state only
  double lattice = 0.0;      // 1D lattice spacing a; 0 means random positions
  Medium medium = Medium::Box;

  bool unbounded() const { return medium == Medium::Unbounded; }

  // Side of the periodic cubic box, L = (N/n)^(1/d); in the unbounded medium the side of the
  // engine's addressable region (unbounded_cells_per_side() cells).
  double box() const;
  // Converts simulation time (diameter / v0) to the paper's unit 1/(v0 n^(1/d)).
  double paper_time(double t) const;
  // Elastic collisions (r = 1; validate() refuses r > 1): the paper's other regime, alpha =
  // 2/(d+2). Every choice between the two regimes asks this, never an exact float comparison.
  bool elastic() const { return restitution >= 1.0; }
  // Sticky coalescence: the exact 1D r = 0 limit of the paper.
  bool sticky() const { return dim == 1 && restitution == 0.0; }
};

// Throws UserError naming the offending input (flag name) if the configuration is impossible.
void validate(const PhysicsConfig& c);

// The medium of a run that names none: unbounded for a kick in 2D and 3D off a lattice, whose
// front then never meets its own periodic images (ensembles agree with box runs whose front is
// far from the edge: tests/sim/test_unbounded_engine.cpp); the box for a thermal gas and in 1D.
Medium default_medium(const PhysicsConfig& c);

// The neighbour grid has at most this many cells per particle (or kMinCellLimit, whichever is
// more): a very dilute gas would otherwise spend gigabytes on empty cells.
inline constexpr double kCellsPerParticle = 16;
inline constexpr double kMinCellLimit = 16777216;  // 2^24 cells, 64 MB of list heads

// Bytes a run of `c` needs at its peak (initial state, engine, and `snapshot_copies` snapshots
// with their text), an estimate to refuse a run before anything is allocated. In the unbounded
// medium: if it made all the --particles it may.
double estimated_bytes(const PhysicsConfig& c, int snapshot_copies = 1);
// What each particle the unbounded medium makes adds to estimated_bytes() with one snapshot: the
// bytes its engine takes from the process's MemoryBudget (sim/memory_budget.h) as it makes them.
double unbounded_bytes_per_particle(const PhysicsConfig& c);
// Throws UserError if estimated_bytes() of a box run exceeds this machine's memory, saying how
// much each is. An unbounded run is not refused here: how far its front gets by --t-max is what
// it measures, and its engine stops it when the memory it makes would not fit.
void check_memory(const PhysicsConfig& c, int snapshot_copies = 1);

// The unbounded medium lives in a periodic grid of cells of side kUnboundedCellSide (just over a
// diameter, exact in binary), whose cells are made only when the front comes near them. Its side
// is 4 times that of the box of the most particles the run may make (--particles) at its
// density: a blast that made them all in a disc or ball would reach less than a third of the way
// to the grid's edge. As many cells per side as the engine's 16-bit cell coordinates and 32-bit
// cell indices allow would do too, but a grid no wider than needed keeps the cell heads the
// front reads close together: the 2D kick of sim/unbounded_vs_box_2d costs 17% more per
// collision than in a box with 32766 cells per side, 9% with 8000.
inline constexpr double kUnboundedCellSide = 1.0 + 0x1p-20;
int unbounded_cells_per_side(const PhysicsConfig& c);
// The lowest --density of the unbounded medium in `dim` (2, 3): the kicked particle's mean free
// path, 1/(2n) for a disc and 1/(pi n) for a sphere, is a tenth of the radius the widest grid
// addresses (16382 cells in 2D, 643 in 3D), so that it leaves the grid before its first
// collision once in e^10 runs. Below it a run would make the empty cells of the whole grid
// (a billion, gigabytes of memory) looking for a particle to kick or for its first collision.
double min_unbounded_density(int dim);

// Highest number density random sequential addition reaches in reasonable time (below the RSA
// jamming limits: packing 0.547 in 2D, Feder 1980; 0.384 in 3D, Talbot et al. 1991).
double max_rsa_density(int dim);

// Sites per side of the smallest simple cubic (square) lattice with at least n sites: a dense
// thermal start is such a lattice, melted (sim/melt.h).
std::int64_t lattice_side(std::int64_t n, int dim);
// Highest number density of a thermal start of n particles. Above max_rsa_density it is a melted
// lattice, which needs a gap between neighbours (a spacing of 1.001 diameters) and stops below
// freezing or a little above it, where a fluid still lasts: packing 0.70 in 2D (the hard-disc
// liquid, Bernard & Krauth 2011), 0.52 in 3D (over freezing at 0.494 the fluid is metastable, but
// crystallises from a thermal start only after far longer than these runs; and 0.5236 is the
// simple cubic lattice's close packing). In 1D the random rods' limit stays.
double max_thermal_density(int dim, std::int64_t n);

// TOML lines, one key per physics flag, readable back with --config; the files that hold them
// (run.toml, movie.toml, ensemble.toml) add their own keys and a comment saying how to rerun.
// The box is left unstated, as in checkpoints written before the medium existed (their physics
// lines must read the same to resume); physics_toml() states it, for the files read back with
// --config, where a missing key means default_medium().
std::string to_toml(const PhysicsConfig& c);
std::string physics_toml(const PhysicsConfig& c);

const char* to_string(Initial i);
const char* to_string(KickSite k);
const char* to_string(Medium m);
// The words of --initial (kick|thermal) and --kick-site (random|centre); UserError otherwise,
// "--initial: 'WORD' is not kick or thermal", the message the command line gives.
Initial parse_initial(const std::string& word);
KickSite parse_kick_site(const std::string& word);
// The words of --medium (box|unbounded).
Medium parse_medium(const std::string& word);

}  // namespace gs
