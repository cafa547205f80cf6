#pragma once
// What one realisation of an ensemble contributes: its time series on the shared logarithmic
// grid and, at the snapshot times, P(R,t), P(v,t), the radial profile and the band packing
// (Jabeen, Rajesh, Ray, EPL 2010, Figs. 2-5). Everything is on binnings fixed by the spec alone,
// so that realisations run anywhere (threads, cluster jobs) can be averaged bin by bin.
//
// A realisation can be written to a folder and read back exactly (shortest round-trip numbers),
// which is what lets `grainshock merge` reproduce the one-shot ensemble to the last bit.
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/band_measures.h"
#include "analysis/table.h"
#include "sim/config.h"
#include "sim/histogram.h"
#include "sim/observables.h"
#include "sim/recorder.h"
#include "sim/snapshot.h"

namespace gs {

// Everything that decides the numbers of an ensemble apart from which realisations it holds.
struct EnsembleSpec {
  PhysicsConfig physics;  // physics.realisation: the first realisation index
  std::uint64_t realisations = 8;
  int per_decade = 20;
  std::vector<double> snapshot_times;  // empty: t_max / 4, t_max / 2, t_max
  int bins = 60;
};

// The scaling exponent of the paper for this physics: 1/(d+1) for r < 1, 2/(d+2) for r = 1.
double theory_alpha(const PhysicsConfig& c);

// Throws UserError naming the flag for impossible specs; fills the default snapshot times.
EnsembleSpec checked(EnsembleSpec spec);

// ensemble.toml: the physics of to_toml() plus the ensemble keys, readable back with --config.
std::string spec_toml(const EnsembleSpec& spec);
// The same text without the keys that say which realisations are held, for comparing the
// physics of folders to merge.
std::string spec_identity(const EnsembleSpec& spec);
// Parses ensemble.toml (UserError naming the file, or `source` for text).
EnsembleSpec read_spec(const std::filesystem::path& file);
EnsembleSpec parse_spec(std::string_view text, const std::string& source);

// Fixed binnings of the snapshot observables at time t: [0, 5 t^alpha] for distances and
// [0, 5 t^(alpha-1)] for speeds, the theory's scales with room for the tails (R_rms ~ 2 t^alpha
// and v_rms ~ 0.6 t^(alpha-1) in 2D for r = 0.1, measured); samples beyond are counted as outside.
Binning radius_binning(const EnsembleSpec& spec, double t);
Binning speed_binning(const EnsembleSpec& spec, double t);
Binning packing_binning(const EnsembleSpec& spec);
// rho / R_front in [0, 1.5]: the core, the band and the few particles ahead of its front.
Binning pressure_binning(const EnsembleSpec& spec);

struct SnapshotMeasures {
  double t = 0;
  Histogram radius, speed;  // P(R,t), P(v,t)
  RadialProfile profile;    // on the radius binning
  // Distribution of the packing fraction of band cells, each cell weighted by its active
  // particles (analysis/band_measures.h).
  Histogram packing;
  BandPacking band;  // typical/upper/mean (fraction lists are not kept)
  BandMeasures measures;
  InnerEdge inner;
  // The kinetic pressure (analysis/core_energy.h) on pressure_binning, of rho / R_front; empty
  // when read from a folder written before it was measured.
  std::vector<double> pressure;
};

// Active particles a realisation needs before its front radius is measured; earlier samples of
// the front_radius column are NaN (there is no band to have a front).
inline constexpr double kFrontMinActive = 50;

// The columns a realisation adds to the Recorder's, from the active particles at each sample
// with N_t >= kFrontMinActive (NaN before): the front radius (analysis/band_measures.h), the
// radial momentum P_r and A of the same particles with their directions redrawn, the finite-N
// floor of an isotropic cloud (sim/observables.h), the share of their kinetic energy held
// behind the band's inner edge (analysis/core_energy.h); then, at every sample, the kicked
// particle's distance from where it started, its speed and its collisions (sim/engine.h
// KickedParticle; NaN where it is not known: 1D, the unbounded medium).
inline constexpr std::array<const char*, 7> kAddedColumns = {
    "front_radius",        "radial_momentum", "anisotropy_isotropic", "core_energy_share",
    "kicked_displacement", "kicked_speed",    "kicked_collisions"};

struct Realisation {
  std::uint64_t index = 0;
  // The columns of Recorder on the shared grid, then kAddedColumns.
  Table timeseries;
  std::vector<SnapshotMeasures> snapshots;  // one per spec snapshot time
};

// Realisation `index` before its first sample: the recorder's columns and front_radius, no rows.
Realisation empty_realisation(const Recorder& recorder, std::uint64_t index);

// Sample times of the shared grid: log_times(0.1, t_max, per_decade) with the snapshot times.
std::vector<double> sample_times(const EnsembleSpec& spec);

// Measures one snapshot on the spec's binnings.
SnapshotMeasures measure_snapshot(const EnsembleSpec& spec, const Snapshot& s);

// Where a realisation keeps its state in flight (analysis/realisation_in_flight.h): the engine and
// the measures taken so far, written every `interval` of wall time and at a stop request, so that
// a realisation of hours stopped or killed goes on from there, to the same bytes.
struct InFlightOptions {
  std::filesystem::path file;  // empty: none is written or read
  // Wall seconds between two writes; 0: never written (one an earlier run left is still read).
  double interval = 0;
  // A state found but unusable (truncated, corrupt, of another build or ensemble): the
  // realisation runs from t = 0, which gives the same bytes, and this hears why (one line).
  std::function<void(const std::string&)> warn;
};

// Runs realisation `index` of the spec, from the state in `in_flight.file` if there is one.
// `on_snapshot` (optional) sees each snapshot before it is dropped (those before a state read
// back are not seen again). Returns false if a stop was requested (the realisation is then
// incomplete and must not be used).
using SnapshotHook = std::function<void(std::uint64_t index, const Snapshot&)>;
bool simulate_realisation(const EnsembleSpec& spec, std::uint64_t index, Realisation& out,
                          const SnapshotHook& on_snapshot = {},
                          const InFlightOptions& in_flight = {});

// Folder layout: timeseries.csv, distributions.csv (one row per snapshot time and bin),
// snapshot_scalars.csv (one row per snapshot time), format (kRealisationFormat and a newline).
inline constexpr std::array<const char*, 4> kRealisationFiles = {
    "timeseries.csv", "distributions.csv", "snapshot_scalars.csv", "format"};
// What the folder's columns mean, raised whenever they change, so that a folder of another
// build is refused in one line instead of read with columns missing or meaning something else.
// 2: the packing scan (cells of 5 and 20, Voronoi median) and the kicked particle's columns;
// 1 (no format file): before them.
inline constexpr const char* kRealisationFormat = "grainshock realisation 2";
struct RealisationFile {
  std::string name, text;
};
// The folder's files as text (what an ensemble sends between processes), and back; `dir` names
// the folder in error messages.
std::vector<RealisationFile> realisation_files(const Realisation& r);
Realisation parse_realisation(const std::vector<RealisationFile>& files, std::uint64_t index,
                              const std::filesystem::path& dir);
// Writes the folder whole or not at all: into temporary_realisation(dir), renamed when complete,
// so a killed ensemble leaves finished realisations and temporaries, never half a realisation.
void write_realisation(const std::filesystem::path& dir, const std::vector<RealisationFile>& files);
// ".NAME.tmp.PID" beside the folder NAME; leftovers of killed writers start with "." and hold
// ".tmp.".
std::filesystem::path temporary_realisation(const std::filesystem::path& dir);
Realisation read_realisation(const std::filesystem::path& dir, std::uint64_t index);

}  // namespace gs
