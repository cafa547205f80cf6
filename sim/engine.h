#pragma once
// Event-driven molecular dynamics of unit hard spheres in a periodic box (Rapaport, "The Art of
// Molecular Dynamics Simulation", ch. 14; Smallenburg, arXiv:2201.01458 for the one-event-per-
// particle bookkeeping).
//
// Each moving particle owns exactly one slot in the event queue: the earlier of its predicted
// collision and its next cell crossing. A collision prediction remembers the partner's collision
// counter; if the partner has changed velocity since, the event is stale and the particle simply
// predicts again. Positions are updated lazily (each particle keeps the time its position refers
// to). A particle that has never moved is in no list but its cell's and costs nothing, so a kick
// run costs what its active particles cost, not what N costs. In a kick in a box (2D, 3D) such
// particles are not even engine records: they wait in a RestingStore (sim/resting_store.h), a
// position each, and become records (Engine::promote) when something first collides with them.
//
// In the unbounded medium (--medium unbounded) the box is a grid far larger than a front ever
// gets, whose cells are made only when a moving particle's stencil first reaches them: their
// particles come from UnboundedMedium (sim/unbounded_medium.h) and are appended at rest, so a run
// holds the particles near the front and pays nothing for the rest. The per-particle arrays are
// reserved up front for the most particles the run may make (--particles) and grown into, so the
// hot loop never reallocates; the cell heads are zero pages until their cell is made.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

#include "sim/cell_grid.h"
#include "sim/collision.h"
#include "sim/config.h"
#include "sim/event_queue.h"
#include "sim/huge_pages.h"
#include "sim/initial.h"
#include "sim/memory_budget.h"
#include "sim/resting_store.h"
#include "sim/snapshot.h"
#include "sim/state_stream.h"
#include "sim/unbounded_medium.h"
#include "sim/vec.h"
#include "sim/zero_pages.h"

namespace gs {

// Observables of the moving particles at one instant, with the definitions of docs/design.md.
struct Sample {
  double t = 0;
  std::int64_t active = 0;  // particles that have collided at least once
  double energy = 0;        // total kinetic energy (unit masses)
  double radius_rms = 0;    // rms distance of active particles from their centre of mass
  double speed_rms = 0;     // rms speed of active particles
  double anisotropy = 0;    // A of the active particles' gyration tensor (sim/observables.h)
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  std::int64_t collisions = 0;
  std::int64_t events = 0;
};

// The kicked particle of a kick in a box (2D, 3D), which starts at the box centre (sim/initial.h):
// the "impurity" of Kumar, Dhar and Krapivsky (arXiv:2505.02225, 2025). Not known in 1D, in
// thermal starts and in the unbounded medium, whose kicked record is not kept in its state.
struct KickedParticle {
  bool known = false;
  std::int32_t tag = -1;  // its index in the initial state and in snapshots
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // unwrapped position - box centre
  double speed = 0;
  std::int64_t collisions = 0;  // velocity-changing collisions it took part in
};

struct EngineStats {
  std::int64_t events = 0;      // everything popped from the queue
  std::int64_t collisions = 0;  // velocity-changing collisions
  std::int64_t inelastic = 0;   // of which dissipated energy (normal speed above the cutoff)
  std::int64_t crossings = 0;   // cell crossings
  std::int64_t stale = 0;       // predictions invalidated by a partner's collision
  std::int64_t overlaps = 0;    // collisions of a pair found deeper than 1e-9 inside contact
  double max_overlap = 0;       // deepest of those
  double virial = 0;            // sum of impulse x contact distance, for the pressure
};

enum class EventKind { None, Collision, Crossing, Stale };

// The dimension-erased face of an engine, for the command line and other drivers. Virtual calls
// stop here: run_until() runs the hot loop of the concrete Engine<D>.
class Simulation {
 public:
  virtual ~Simulation() = default;
  virtual int dim() const = 0;
  virtual const PhysicsConfig& config() const = 0;
  // Processes every event up to time t and leaves the clock at t; or, once a stop is asked for
  // (sim/stop.h), returns within kStopPollEvents events with the clock at the last one.
  virtual void run_until(double t) = 0;
  static constexpr std::int64_t kStopPollEvents = std::int64_t{1} << 16;
  // Processes the next event only (for tests and debugging).
  virtual EventKind step() = 0;
  virtual double time() const = 0;
  // The particles held: N in a box, those made so far in the unbounded medium.
  virtual std::int64_t particle_count() const = 0;
  virtual Sample sample() const = 0;
  // The state now, into `out`, reusing its storage: frame loops take one every frame, and a
  // fresh 2.5e5-particle snapshot costs its page faults every time.
  virtual void snapshot(Snapshot& out) const = 0;
  Snapshot snapshot() const {
    Snapshot s;
    snapshot(s);
    return s;
  }
  // The active particles only, in the order snapshot() gives them (active_subset of it, to the
  // bit), at the cost of the particles that have moved: those at rest are never visited.
  virtual void active_snapshot(Snapshot& out) const = 0;
  // Unwrapped positions of the active particles, in no set order: what the front radius needs at
  // every sample of an ensemble without copying a whole snapshot (the particles at rest cost
  // nothing).
  virtual void active_positions(std::vector<Eigen::Vector3d>& out) const = 0;
  virtual const EngineStats& stats() const = 0;
  virtual KickedParticle kicked_particle() const = 0;
  // Deepest overlap (1 - distance) of any pair now, by a scan of all cells; 0 if none.
  virtual double max_overlap_now() const = 0;
  // The whole state, derived structures included (cell lists, queue, predictions), so that a
  // simulation loaded from it makes the same events in the same order, ties included.
  virtual void save(StateWriter& out) const = 0;
};

std::unique_ptr<Simulation> make_simulation(const PhysicsConfig& c);
// A simulation of `c` in the state save() wrote; refuses (UserError) one of other physics.
std::unique_ptr<Simulation> load_simulation(const PhysicsConfig& c, StateReader& in);

template <int D>
class Engine final : public Simulation {
 public:
  Engine(const PhysicsConfig& c, InitialState<D> init);
  // A kick in the unbounded medium (c.unbounded(), D = 2 or 3): the particle nearest the box
  // centre is kicked, and the medium is made around it as the front spreads.
  explicit Engine(const PhysicsConfig& c);
  Engine(const PhysicsConfig& c, StateReader& in);

  int dim() const override { return D; }
  const PhysicsConfig& config() const override { return config_; }
  void run_until(double t) override;
  EventKind step() override;
  double time() const override { return now_; }
  std::int64_t particle_count() const override { return size(); }
  Sample sample() const override;
  void snapshot(Snapshot& s) const override;
  using Simulation::snapshot;
  void active_snapshot(Snapshot& s) const override;
  void active_positions(std::vector<Eigen::Vector3d>& out) const override;
  const EngineStats& stats() const override { return stats_; }
  KickedParticle kicked_particle() const override;
  double max_overlap_now() const override;
  void save(StateWriter& out) const override;

  // The particles held: the moving records and those still at rest.
  std::int32_t size() const { return moving() + static_cast<std::int32_t>(rest_.resting()); }

 private:
  EventKind process_next();
  void advance(std::int32_t i);
  Vec<D> position(std::int32_t i) const;  // a record's, now, unwrapped
  std::int32_t moving() const { return static_cast<std::int32_t>(kin_.size()); }
  Vec<D> separation(const Vec<D>& xi, std::int32_t j) const;
  // The particles a search will test, other than the searching one: records (who) and slots
  // of the resting store (rest). A stencil is at most 4.5 diameters wide (cells are under 1.5
  // wide when there are two or more per side, and a lone cell is under 2 wide), so its spheres
  // lie in a cube of side 5.5 and cannot number more than 5.5^3 / (pi / 6) < 320.
  struct Neighbours {
    static constexpr int kMax = 320;
    int count = 0, rest_count = 0;
    std::int32_t who[kMax];
    std::int32_t rest[kMax];
  };
  // kMakes: the unbounded medium, whose cells are made as they come into reach (a box's all
  // exist; the two are apart so that a box pays nothing for the test).
  template <bool kMakes, class ForEachCell>
  void gather(std::int32_t i, Neighbours& nb, ForEachCell&& for_each_cell);
  template <class ForEachCell>
  void gather_cells(std::int32_t i, Neighbours& nb, ForEachCell&& for_each_cell) {
    if (medium_)
      gather<true>(i, nb, for_each_cell);
    else
      gather<false>(i, nb, for_each_cell);
  }
  void gather_stencil(std::int32_t i, Neighbours& nb);
  void search(std::int32_t i, const Vec<D>& xi, const Neighbours& nb);
  void search_resting(std::int32_t i, const Vec<D>& xi, const Neighbours& nb, double& best);
  // A prediction's partner: a record (>= 0), none (-1), or resting slot r as -2 - r.
  static std::int32_t resting_partner(std::int32_t r) { return -2 - r; }
  // Whether i's predicted partner has changed course since the prediction.
  bool partner_changed(std::int32_t i) const;
  // The record of resting slot r's particle, made now.
  std::int32_t promote(std::int32_t r);
  // Drops the store's dead slots (RestingStore::compact) and renames the slots predictions name.
  void compact_store();
  void predict(std::int32_t i);
  void predict_from(std::int32_t i, const Neighbours& nb);
  void predict_crossing(std::int32_t i, const Vec<D>& xi);
  void schedule(std::int32_t i);
  void collide_pair(std::int32_t i, std::int32_t j);
  void collide_sticky(std::int32_t i, std::int32_t j);
  void cross_cell(std::int32_t i);
  // The particles' indices in Morton order of their cells (the records' order, tag_).
  std::vector<std::int32_t> cell_order(const VecArray<D>& position) const;
  void mark_moving(std::int32_t i);
  void mark_active(std::int32_t i);
  void snapshot_info(Snapshot& s) const;  // the header every snapshot shares
  void cell_insert(std::int32_t i, std::int32_t cell);
  void cell_remove(std::int32_t i, std::int32_t cell);
  void reserve_particles(std::size_t n);
  // A new record at rest since t = 0 or moving from it, in its cell: its index.
  std::int32_t add_record(const Vec<D>& x, const Vec<D>& v, std::int32_t tag, const IVec<D>& cell);
  [[gnu::cold]] void make_cell(std::int32_t cell);  // the unbounded medium: appends its particles
  // Takes the memory of `n` more made particles from the process's budget, or ends the run.
  void take_memory(std::size_t n);
  void kick_nearest_centre();

  PhysicsConfig config_;
  CellGrid<D> grid_;
  double now_ = 0;
  EngineStats stats_;

  // What a neighbour search reads of each particle it meets, packed into one cache line: a
  // property per array would cost four cache misses per neighbour instead of one (the search is
  // most of the run time). x is wrapped into the box and refers to time t; image_ counts box
  // crossings so that unwrapped positions can be rebuilt exactly.
  struct alignas(64) Kinematics {
    Vec<D> x;
    double t;
    Vec<D> v;
    std::uint32_t counter;  // bumped at every velocity change
    // Has ever moved / collided. Here and not in arrays of their own, because every collision
    // sets them and the line is at hand: at N = 2e6 flag arrays miss the cache and the TLB.
    bool moving = false, active = false;
  };
  HugeVector<Kinematics> kin_;
  std::vector<std::int32_t> tag_;  // the particle's index in the initial state and in snapshots
  // Box crossings per record, for every record the engine may hold, in zero pages: a kick's
  // front never reaches the box's edge (and the unbounded medium has none), so its images are
  // never written and cost nothing (12 B a moving sphere); a thermal gas
  // touches them as its particles wrap.
  using Image = std::array<std::int32_t, D>;
  ZeroPages<Image> image_;

  // The records of each cell as singly linked lists, apart from the particle data: a search walks
  // them without waiting for each particle's cache line. A cell's head holds its first record
  // plus head_offset_, so that an untouched zero page is an empty cell: in a box the offset is 1,
  // in the unbounded medium 2, where 1 is an empty cell and 0 a cell not made yet, which a search
  // reads as empty.
  static constexpr std::int32_t kEmptyCell = 1, kUnmadeCell = 0;
  std::int32_t head_offset_ = 1;
  ZeroPages<std::int32_t> head_;
  HugeVector<std::int32_t> next_;

  // The next event of each particle (best collision and next crossing) and its cell, in one half
  // cache line: every event reads all of it, and cells in an array of their own cost one more
  // cache miss per event (3% at packing 0.5). Cell coordinates fit in 16 bits in 2D and 3D
  // (validate() bounds the box side); a 1D box can be far longer.
  using CellCoord = std::conditional_t<D == 1, std::int32_t, std::int16_t>;
  struct alignas(32) Prediction {
    double coll_time = kNever;
    double cross_time = kNever;
    std::int32_t partner = -1;
    std::uint32_t partner_counter = 0;  // the partner's counter when predicted
    CellCoord cell[D] = {};             // the particle's cell
    std::int8_t cross_dir = 0;          // 2 * dimension + (1 if upwards)
  };
  static_assert(sizeof(Prediction) == 32);
  IVec<D> cell_of(std::int32_t i) const {
    IVec<D> c;
    for (int k = 0; k < D; ++k) c[k] = pred_[i].cell[k];
    return c;
  }
  void set_cell(std::int32_t i, const IVec<D>& c) {
    for (int k = 0; k < D; ++k) pred_[i].cell[k] = static_cast<CellCoord>(c[k]);
  }
  HugeVector<Prediction> pred_;
  EventQueue queue_;
  Neighbours near_[2];  // scratch of the searches: the two spheres of a collision

  std::vector<double> first_collision_;
  // Every record that has ever moved, in the order it first moved; none kept where the records
  // are made as they are first hit (rests_), which are that list already.
  std::vector<std::int32_t> moved_;
  template <class F>
  void for_each_moved(F&& f) const {
    if (rests_)
      for (std::int32_t i = 0; i < moving(); ++i) f(i);
    else
      for (std::int32_t i : moved_) f(i);
  }

  // The particles of a kick in a box that have never been hit: in 2D and 3D (rests_), none in
  // 1D, whose sticky clusters keep every particle a record in order along the line, in thermal
  // starts, where all move, nor in the unbounded medium (make_cell).
  static constexpr bool kRests = D > 1;
  bool rests_ = false;
  RestingStore<D> rest_;
  // The store is compacted when it holds as many dead slots as there were records after the last
  // compaction, and at least a 64th of its slots: a pass over the store per doubling of the
  // records, which costs each new record at most 64 slots' moves (particles at rest cost
  // nothing), and never more dead slots than records once a 64th of the particles have moved.
  static constexpr std::int64_t kCompactAt = 1024;
  std::int64_t compact_at_ = 0;
  std::int64_t next_compaction() const {
    return std::max({kCompactAt, std::int64_t{moving()}, std::int64_t{rest_.slots()} / 64});
  }

  // The unbounded medium (none in a box): its generator, the cells made so far in the order they
  // were made (what a checkpoint keeps of the grid), a cell's new particles, and the most
  // particles the run may make. The generator's memo is dropped past kMemoCandidates (about
  // 40 MB), or past kMemoBytes in all, which a dilute medium's empty cells (4 B each) reach
  // first; what it makes does not depend on it.
  static constexpr std::size_t kMemoCandidates = std::size_t{1} << 20;
  static constexpr std::size_t kMemoBytes = std::size_t{1} << 27;
  std::unique_ptr<UnboundedMedium<D>> medium_;
  std::vector<std::int32_t> made_;
  VecArray<D> fresh_;
  std::size_t capacity_ = 0;
  BudgetShare memory_;  // what the made particles take of the process's memory
  std::int64_t bytes_each_ = 0;  // what each takes of it (unbounded_bytes_per_particle)

  // Sticky clusters (1D, r = 0): particles are indexed along the line, a cluster is a cyclic
  // index range, and its two ends know each other.
  std::vector<std::int32_t> cluster_lo_, cluster_hi_;
};

}  // namespace gs
