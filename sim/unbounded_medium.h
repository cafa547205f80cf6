#pragma once
// The gas at rest of an unbounded medium, made cell by cell where it is asked for.
//
// Construction: infinite-volume random sequential addition (RSA) with Poisson arrivals in
// space x time (Penrose 2001, "Random parking, sequential adsorption, and the jamming limit").
// Candidates form a Poisson process of `candidate_density` rho per unit volume, each with a
// uniform arrival time in [0, 1); a candidate is accepted iff no accepted candidate that arrived
// earlier lies within one diameter. Every cell of side s >= 1 draws its Poisson(rho s^d)
// candidates from its own stream (seed, realisation, Stream::Medium, cell), so the candidates are
// a fixed function of the key. Acceptance is a local rule: deciding a candidate needs only the
// earlier candidates within one diameter, each decided the same way; arrival times strictly
// decrease along that chain, and the expected number of chains of length k is (v rho)^k / k!
// (v the excluded volume), so it ends after a few steps whatever rho. Decisions are memoised
// per candidate, so the particles of a cell are the same whatever order cells are asked in,
// and on resume (a checkpoint needs only the set of cells already made, not the memo).
// This is exact: it is the thermodynamic limit of RSA in a box stopped after rho V trials, with
// no edges, no period and no approximation. The box runs (sim/initial.h) stop RSA at a fixed N
// instead of a fixed number of trials; the two differ only by fluctuations of order 1/sqrt(N)
// (the trial count at which N is reached fluctuates), so their local structure agrees and only
// the box's total count is pinned. rho is chosen so that the accepted density equals the box
// runs' number density: exactly by Renyi's formula in 1D, by a table measured once with this
// generator in 2D and 3D (`calibrate_medium`, values and their error in unbounded_medium.cpp).
//
// In 1D the box runs start from the uniform hard-rod gas (random_rods in sim/initial.cpp), not
// RSA; this medium in 1D is RSA (Renyi's car parking) at the same density: its g(r) differs.
//
// How the engine uses it (`--medium unbounded`, sim/engine.h): the engine's cells are this
// medium's cells (side kUnboundedCellSide, sim/config.h). Whenever a moving particle's 3^d stencil
// comes to include a cell not yet made (a cell crossing brings a new layer into reach; the kick
// goes to the particle nearest the origin once the cells around it are made), the engine calls
// `particles(cell)` before it searches, appends them at rest and marks the cell made; a cell is
// made once. The checkpoint holds the list of made cells and their heads with the particles'
// state, and the generator's memo is a cache that the engine drops past a bound.
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "sim/rng.h"
#include "sim/vec.h"

namespace gs {

struct MediumOptions {
  int dim = 2;
  double density = 0.25;  // particles per unit volume (diameter 1), as --density
  double cell_side = 1.0;  // side of a cell, >= 1 (the medium depends on it: part of the key)
  std::uint64_t seed = 1;
  std::uint64_t realisation = 0;
};

// The candidate density rho whose infinite-volume RSA has `density` particles per unit volume in
// dimension `dim`. Throws UserError naming --density if density is not in (0, the table's end].
double medium_candidate_density(int dim, double density);
// The largest number density the calibration covers in `dim` (packing 0.40 in 2D, 0.26 in 3D,
// 0.70 in 1D).
double medium_max_density(int dim);
// The accepted density of 1D RSA after rho candidates per unit length (Renyi 1958): the exact
// curve the 1D medium is checked against.
double renyi_density(double rho);

template <int D>
class UnboundedMedium {
 public:
  using Cell = std::array<std::int64_t, D>;

  explicit UnboundedMedium(const MediumOptions& o);
  // Straight from a candidate density (the calibration and its tests).
  UnboundedMedium(double candidate_density, double cell_side, std::uint64_t seed,
                  std::uint64_t realisation);

  // Appends to `out` the resting particles whose centres lie in the cell
  // [cell * s, (cell + 1) * s)^D, in the order the cell's stream drew them.
  void particles(const Cell& cell, VecArray<D>& out);
  // The same with the arrival time of each (the calibration counts particles by arrival).
  void particles(const Cell& cell, VecArray<D>& out, std::vector<double>& arrival);

  double candidate_density() const { return rho_; }
  double cell_side() const { return side_; }
  // Cells whose candidates are held (the blocks of those asked for and of those their chains
  // reached).
  std::size_t cached_cells() const { return blocks_.size() * kBlockCells; }
  std::size_t cached_candidates() const { return pool_.size(); }
  // Heap bytes the memo holds (candidates, cell table), for the bench's bytes per particle.
  std::size_t memory_bytes() const;
  // Drops the memo; what `particles` returns afterwards is unchanged.
  void clear();

 private:
  struct Candidate {
    Vec<D> x;
    double t;
    std::int8_t state;  // 0 undecided, 1 accepted, -1 rejected
  };
  // Cells are drawn a block at a time (each still from its own stream, so the medium does not
  // depend on the blocks): one table entry per block, four bytes per cell.
  static constexpr int kShift = D == 1 ? 8 : D == 2 ? 4 : 3;  // a block is 2^kShift cells wide
  static constexpr int kBlock = 1 << kShift;
  static constexpr int kBlockCells = D == 1 ? 256 : D == 2 ? 256 : 512;
  struct CellHash {
    std::size_t operator()(const Cell& c) const;
  };
  struct Block {
    std::uint32_t first_candidate, first_offset;
  };
  struct Range {
    std::uint32_t first, count;
  };

  static constexpr int kStencil = D == 1 ? 3 : D == 2 ? 9 : 27;
  Range cell(const Cell& c);  // draws the cell's block the first time
  const Block& block(const Cell& b);
  void draw_block(const Cell& block);
  void seed_rows(const Cell& block);
  // The candidates of the cells lo..hi (2 or 3 a side) into stencil_, unless they are there.
  void gather(const Cell& lo, const Cell& hi);
  bool accepted(std::uint32_t i);
  static bool earlier(const Candidate& a, const Candidate& b);

  double rho_, side_;
  struct Piece {
    double mean, p0;  // p0 = e^-mean
  };
  std::vector<Piece> pieces_;
  // The streams' shared seeding: (seed, realisation, Stream::Medium), then per row of the block
  // being drawn its leading coordinates (all but the last), one row per kBlock cells.
  RngSeed medium_seed_;
  std::array<RngSeed, kBlockCells / kBlock> row_seeds_;
  std::vector<Candidate> pool_;  // indices stay valid as it grows
  std::vector<std::uint32_t> offsets_;  // per block, kBlockCells + 1 starts within the block
  std::unordered_map<Cell, Block, CellHash> blocks_;
  // The blocks found lately, direct-mapped by their coordinates: a candidate's decision looks at
  // 3^D cells, which straddle two blocks along an axis a quarter of the time in 3D, and a table
  // lookup costs more than all the rest of finding a cell.
  static constexpr int kRecent = D == 1 ? 4 : D == 2 ? 16 : 64;  // 4^D: two bits an axis
  struct Recent {
    Cell key;
    Block block;
    bool valid = false;
  };
  std::array<Recent, kRecent> recent_{};
  // The candidates' ranges of the cells lo..hi that a decision looked at last: the candidates of
  // one cell, decided one after the other, nearly always look at the same cells.
  Cell stencil_lo_{}, stencil_hi_{};
  bool stencil_valid_ = false;
  int stencil_count_ = 0;
  std::array<Range, kStencil> stencil_;
  std::vector<std::uint32_t> stack_;   // candidates being decided
  std::vector<std::uint32_t> nearby_;  // scratch: earlier candidates within a diameter
};

}  // namespace gs
