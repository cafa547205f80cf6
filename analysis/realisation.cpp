#include "analysis/realisation.h"

#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "analysis/core_energy.h"
#include "analysis/realisation_in_flight.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/escaped.h"
#include "sim/format.h"
#include "sim/recorder.h"
#include "sim/stop.h"

namespace gs {
namespace {

constexpr double kRadiusRange = 5, kSpeedRange = 5;
// Wall time between two writes of a state in flight, at least, in units of the last write's
// duration (InFlightOptions::interval if longer): writing costs 2% of the run at most.
constexpr double kWriteSpacing = 50;

std::string times_text(const std::vector<double>& t) {
  std::string s = "[";
  for (std::size_t i = 0; i < t.size(); ++i) s += (i ? ", " : "") + format_double(t[i]);
  return s + "]";
}

// Histogram <-> columns of distributions.csv.
void put_histogram(Table& rows, std::size_t first, const Histogram& h, const std::string& name) {
  auto& lo = rows.column(name + "_lo");
  auto& hi = rows.column(name + "_hi");
  auto& p = rows.column("P_" + name);
  for (std::size_t b = 0; b < h.bins(); ++b) {
    lo[first + b] = h.edges[b];
    hi[first + b] = h.edges[b + 1];
    p[first + b] = h.values[b];
  }
}

Histogram get_histogram(const Table& rows, std::size_t first, std::size_t bins,
                        const std::string& name, double samples, double outside) {
  Histogram h;
  const auto& lo = rows.column(name + "_lo");
  const auto& hi = rows.column(name + "_hi");
  const auto& p = rows.column("P_" + name);
  for (std::size_t b = 0; b < bins; ++b) {
    h.edges.push_back(lo[first + b]);
    h.values.push_back(p[first + b]);
  }
  h.edges.push_back(hi[first + bins - 1]);
  h.samples = static_cast<std::uint64_t>(samples);
  h.outside = static_cast<std::uint64_t>(outside);
  return h;
}

const std::vector<std::string> kDistributionColumns = {"t",
                                                       "bin",
                                                       "R_lo",
                                                       "R_hi",
                                                       "P_R",
                                                       "v_lo",
                                                       "v_hi",
                                                       "P_v",
                                                       "profile_count",
                                                       "profile_density",
                                                       "profile_speed_sum",
                                                       "profile_radial_velocity_sum",
                                                       "packing_lo",
                                                       "packing_hi",
                                                       "P_packing",
                                                       "pressure"};

const std::vector<std::string> kScalarColumns = {"t",
                                                 "R_samples",
                                                 "R_outside",
                                                 "v_samples",
                                                 "v_outside",
                                                 "packing_samples",
                                                 "packing_outside",
                                                 "packing_typical",
                                                 "packing_upper",
                                                 "packing_mean",
                                                 "packing_cell_side",
                                                 "inner_correlation",
                                                 "inner_median_radius",
                                                 "inner_speed",
                                                 "outer_speed",
                                                 "inner_outer_ratio",
                                                 "front_radius",
                                                 "shell_peak_density",
                                                 "packing_densest_cell",
                                                 "packing_local_median",
                                                 "packing_local_upper",
                                                 "packing_cell5",
                                                 "packing_cell20",
                                                 "packing_voronoi_median"};

// One line naming the folder when it was written with other columns (kRealisationFormat).
void check_format(const std::vector<RealisationFile>& files, const std::filesystem::path& dir) {
  const std::string want = std::string(kRealisationFormat) + "\n";
  for (const auto& f : files)
    if (f.name == kRealisationFiles[3]) {
      if (f.text == want) return;
      throw UserError(dir.string() + ": realisation of another format ('" +
                      escaped(f.text.substr(0, f.text.find('\n'))) + "', this build reads '" +
                      kRealisationFormat + "'); remove it to run it again");
    }
  throw UserError(dir.string() + ": realisation of an older grainshock (no format file; this " +
                  "build reads '" + kRealisationFormat + "'); remove it to run it again");
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw UserError("cannot read " + file.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

double theory_alpha(const PhysicsConfig& c) {
  return !c.elastic() ? 1.0 / (c.dim + 1) : 2.0 / (c.dim + 2);
}

EnsembleSpec checked(EnsembleSpec spec) {
  validate(spec.physics);
  if (spec.physics.initial != Initial::Kick)
    throw UsageError("--initial: ensembles average kicked gases only (use run for thermal starts)");
  if (spec.physics.dim < 2) throw UsageError("--dim: ensembles measure bands in 2 or 3 dimensions");
  if (spec.realisations < 1) throw UsageError("--realisations must be at least 1");
  if (spec.per_decade < 1 || spec.per_decade > 1000)
    throw UsageError("--per-decade must be in [1, 1000]");
  if (spec.bins < 2 || spec.bins > 100000) throw UsageError("--bins must be in [2, 100000]");
  const double T = spec.physics.t_max;
  if (spec.snapshot_times.empty()) spec.snapshot_times = {T / 4, T / 2, T};
  std::sort(spec.snapshot_times.begin(), spec.snapshot_times.end());
  for (double t : spec.snapshot_times)
    if (!(t > 0 && t <= T))
      throw UsageError("--snapshot-times: " + format_number(t) + " is outside (0, t-max]");
  spec.snapshot_times = merge_times(spec.snapshot_times, {});
  return spec;
}

std::string spec_identity(const EnsembleSpec& spec) {
  PhysicsConfig p = spec.physics;
  p.realisation = 0;
  std::string toml = physics_toml(p);
  // Drop the run comment and the realisation key: they say what is held, not what is simulated.
  std::istringstream in(toml);
  std::ostringstream out;
  for (std::string line; std::getline(in, line);)
    if (!line.starts_with("#") && !line.starts_with("realisation = ")) out << line << "\n";
  out << "per-decade = " << spec.per_decade << "\n";
  out << "snapshot-times = " << times_text(spec.snapshot_times) << "\n";
  out << "bins = " << spec.bins << "\n";
  return out.str();
}

std::string spec_toml(const EnsembleSpec& spec) {
  std::ostringstream o;
  o << "# grainshock ensemble; rerun with: grainshock ensemble --config ensemble.toml\n";
  o << "# realisation = first realisation index; realisations = how many\n";
  o << "realisation = " << spec.physics.realisation << "\n";
  o << "realisations = " << spec.realisations << "\n";
  o << spec_identity(spec);
  return o.str();
}

EnsembleSpec parse_spec(std::string_view text, const std::string& source) {
  toml::table t;
  try {
    t = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw UserError(source + ": malformed TOML at line " + std::to_string(e.source().begin.line));
  }
  auto need = [&](const char* key) -> const toml::node& {
    const toml::node* n = t.get(key);
    if (n == nullptr) throw UserError(source + ": key '" + key + "' missing");
    return *n;
  };
  auto num = [&](const char* key) {
    const auto& n = need(key);
    if (auto v = n.value<double>()) return *v;
    throw UserError(source + ": key '" + key + "' is not a number");
  };
  auto integer = [&](const char* key) {
    const auto& n = need(key);
    if (auto v = n.value<std::int64_t>()) return *v;
    throw UserError(source + ": key '" + key + "' is not an integer");
  };
  auto str = [&](const char* key) {
    const auto& n = need(key);
    if (auto v = n.value<std::string>()) return *v;
    throw UserError(source + ": key '" + key + "' is not a string");
  };
  EnsembleSpec s;
  PhysicsConfig& p = s.physics;
  p.dim = static_cast<int>(integer("dim"));
  p.particles = integer("particles");
  p.density = num("density");
  p.restitution = num("restitution");
  p.cutoff = num("cutoff");
  p.speed = num("speed");
  p.seed = static_cast<std::uint64_t>(integer("seed"));
  p.realisation = static_cast<std::uint64_t>(integer("realisation"));
  p.t_max = num("t-max");
  const std::string initial = str("initial"), site = str("kick-site");
  if (initial != to_string(Initial::Kick)) throw UserError(source + ": initial must be kick");
  p.initial = Initial::Kick;
  if (site == to_string(KickSite::Centre))
    p.kick_site = KickSite::Centre;
  else if (site == to_string(KickSite::Random))
    p.kick_site = KickSite::Random;
  else
    throw UserError(source + ": unknown kick-site '" + site + "'");
  p.temperature = num("temperature");
  p.lattice = num("lattice");
  // Files written before the medium existed have none, and mean the box.
  if (const toml::node* m = t.get("medium")) {
    const auto word = m->value<std::string>();
    if (!word) throw UserError(source + ": key 'medium' is not a string");
    p.medium = parse_medium(*word);
  }
  s.realisations = static_cast<std::uint64_t>(integer("realisations"));
  s.per_decade = static_cast<int>(integer("per-decade"));
  s.bins = static_cast<int>(integer("bins"));
  const auto* arr = need("snapshot-times").as_array();
  if (arr == nullptr) throw UserError(source + ": key 'snapshot-times' is not an array");
  for (auto&& el : *arr) {
    auto v = el.value<double>();
    if (!v) throw UserError(source + ": snapshot-times holds a non-number");
    s.snapshot_times.push_back(*v);
  }
  try {
    return checked(s);
  } catch (const UserError& e) {
    throw UserError(source + ": " + e.what());
  }
}

EnsembleSpec read_spec(const std::filesystem::path& file) {
  return parse_spec(read_text(file), file.string());
}

Binning radius_binning(const EnsembleSpec& spec, double t) {
  return {.bins = spec.bins, .lo = 0, .hi = kRadiusRange * std::pow(t, theory_alpha(spec.physics))};
}

Binning speed_binning(const EnsembleSpec& spec, double t) {
  const double a = theory_alpha(spec.physics);
  return {.bins = spec.bins, .lo = 0, .hi = kSpeedRange * spec.physics.speed * std::pow(t, a - 1)};
}

Binning packing_binning(const EnsembleSpec& spec) {
  return {.bins = spec.bins, .lo = 0, .hi = 1};
}

Binning pressure_binning(const EnsembleSpec& spec) {
  return {.bins = spec.bins, .lo = 0, .hi = 1.5};
}

std::vector<double> sample_times(const EnsembleSpec& spec) {
  return merge_times(log_times(0.1, spec.physics.t_max, spec.per_decade), spec.snapshot_times);
}

namespace {

// The unbounded medium's snapshot moved into a periodic box just larger than what has been made,
// for the band measures, whose cell grids span the whole box: its own box is the engine's
// addressable region (32766^2 cells in 2D), almost all of it never made. Particles on opposite
// faces stay `margin` apart across the wrap, more than any cell those measures use, so the wrap
// adds no neighbours; the densest-cell grid's side is box / floor(box / 10), about 10 as in a box.
Snapshot compact_box(const Snapshot& s, double margin) {
  Snapshot out = s;
  const int d = s.info.dim;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, extent = 0;
  for (const auto& x : s.position)
    for (int k = 0; k < d; ++k) lo[k] = std::min(lo[k], x[k]);
  for (auto& x : out.position)
    for (int k = 0; k < d; ++k) {
      x[k] += margin - lo[k];
      extent = std::max(extent, x[k] + margin);
    }
  out.info.set_cubic_box(extent);
  out.info.origin.setZero();
  return out;
}

}  // namespace

SnapshotMeasures measure_snapshot(const EnsembleSpec& spec, const Snapshot& s) {
  SnapshotMeasures m;
  m.t = s.info.time;
  const Snapshot active = active_subset(s);
  m.radius = radial_distribution(active, radius_binning(spec, m.t));
  m.speed = speed_distribution(active, speed_binning(spec, m.t));
  m.profile = radial_profile(active, radius_binning(spec, m.t));
  PackingOptions po;
  po.binning = packing_binning(spec);
  m.band = band_packing(s, po);  // counts the particles at rest in the band's cells too
  m.packing = weighted_cell_histogram(m.band.fraction, m.band.active, po.binning);
  // The packing readings answer the paper's 2D numbers; in 3D (2e6 spheres, 64 shifted grids)
  // they would cost seconds per snapshot for nothing the paper states, so only the front is
  // measured there.
  if (spec.physics.dim == 2 && spec.physics.unbounded())
    m.measures = measure_band(compact_box(s, 2 * BandMeasureOptions{}.cell), spec.physics.density);
  else if (spec.physics.dim == 2)
    m.measures = measure_band(s, spec.physics.density);
  else
    m.measures.front = measure_front(s, spec.physics.density);
  m.band.fraction.clear();
  m.band.active.clear();
  m.inner = inner_edge_speed(active);
  // Without a band (no front) there is no rho / R_front to bin: none, rather than zeros. The
  // front is the one measured above (core_energy's own is the same rule on the same particles).
  const double front = m.measures.front.radius;
  if (std::isfinite(front))
    m.pressure = kinetic_pressure(active, front, pressure_binning(spec)).pressure;
  return m;
}

namespace {

// P_r, A's isotropic floor and the core's energy share of the active particles at sample k,
// appended to `row` (NaN while there is no band). The shuffles draw from a stream keyed by the
// sample, so a realisation resumed from its state in flight draws what an unbroken one does.
void add_band_columns(const Simulation& sim, const PhysicsConfig& c, std::uint64_t index,
                      std::size_t k, double active, Snapshot& act, std::vector<double>& row) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (active < kFrontMinActive) {
    row.insert(row.end(), 3, nan);  // P_r, A's floor, the core's share
    return;
  }
  sim.active_snapshot(act);
  row.push_back(radial_momentum(act));
  Rng rng(c.seed, index, Stream::Shuffle, std::array<std::int64_t, 1>{std::int64_t(k)});
  row.push_back(isotropic_anisotropy(act, rng));
  row.push_back(core_energy(act, c.density).share);
}

// The kicked particle's columns (kAddedColumns), appended to `row`.
void add_kicked_columns(const Simulation& sim, std::vector<double>& row) {
  const KickedParticle k = sim.kicked_particle();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  row.push_back(k.known ? k.displacement.norm() : nan);
  row.push_back(k.known ? k.speed : nan);
  row.push_back(k.known ? double(k.collisions) : nan);
}

}  // namespace

Realisation empty_realisation(const Recorder& recorder, std::uint64_t index) {
  Realisation r;
  r.index = index;
  r.timeseries.names = recorder.columns();
  for (const char* n : kAddedColumns) r.timeseries.names.push_back(n);
  r.timeseries.columns.assign(r.timeseries.names.size(), {});
  return r;
}

bool simulate_realisation(const EnsembleSpec& spec, std::uint64_t index, Realisation& out,
                          const SnapshotHook& on_snapshot, const InFlightOptions& in_flight) {
  PhysicsConfig c = spec.physics;
  c.realisation = index;
  Recorder recorder(c);
  std::size_t first = 0;  // the first sample time still to reach
  std::unique_ptr<Simulation> sim;
  if (!in_flight.file.empty()) {
    try {
      sim = load_in_flight(in_flight.file, spec, index, recorder, out, first);
    } catch (const UserError& e) {
      // Running it again from t = 0 gives the same bytes: the state only saves time.
      if (in_flight.warn)
        in_flight.warn(std::string(e.what()) + "; realisation " + std::to_string(index) +
                       " runs again from t = 0");
      remove_in_flight(in_flight.file);
      recorder = Recorder(c);
    }
  }
  if (!sim) {
    sim = make_simulation(c);
    first = 0;
    out = empty_realisation(recorder, index);
  }
  const auto active_column =
      std::size_t(std::find(recorder.columns().begin(), recorder.columns().end(), "active") -
                  recorder.columns().begin());
  std::size_t next_snap = out.snapshots.size();
  Snapshot s;  // one buffer for every snapshot time: at 2e6 spheres a fresh one is 130 MB
  std::vector<Eigen::Vector3d> active;  // the front radius's input at every sample
  Snapshot act;                         // the active particles at every sample (P_r, A's floor)
  using Clock = std::chrono::steady_clock;
  const bool keeping = !in_flight.file.empty() && in_flight.interval > 0;
  auto kept = Clock::now();
  double wait = in_flight.interval;
  auto keep = [&](std::size_t next_sample) {
    const auto start = Clock::now();
    try {
      save_in_flight(in_flight.file, spec, index, next_sample, *sim, recorder, out);
    } catch (const UserError& e) {
      // The state is insurance against a kill: a full disk must not end a run of hours.
      if (in_flight.warn) in_flight.warn(e.what());
    }
    kept = Clock::now();
    // A 3D state grows to GBs (190 B per made sphere, bench io/in_flight_3d_r0.9: 165 MB
    // written in 2.8 s at t = 1e5), whose writes every 10 min would cost a quarter of the run.
    wait = std::max(in_flight.interval,
                    kWriteSpacing * std::chrono::duration<double>(kept - start).count());
  };
  const std::vector<double> times = sample_times(spec);
  for (std::size_t k = first; k < times.size(); ++k) {
    const double t = times[k];
    // Slices, so that a stop request is seen soon and the state in flight is kept on time: the
    // clock is read once a slice, never per event. A slice of 1% of t is about 1.3% of a
    // realisation's wall time at its end (collisions grow as t^1.26 in 3D), 5 min of a 7 h one;
    // where the slices fall does not change the history (run_until stops between events).
    while (sim->time() < t) {
      sim->run_until(std::min(t, sim->time() + std::max(1.0, 0.01 * sim->time())));
      if (stop_requested()) {
        if (keeping) keep(k);
        return false;
      }
      if (keeping && std::chrono::duration<double>(Clock::now() - kept).count() >= wait) keep(k);
    }
    std::vector<double> row = recorder.row(*sim);
    double front = std::numeric_limits<double>::quiet_NaN();
    if (row[active_column] >= kFrontMinActive) {
      sim->active_positions(active);
      front = front_of(active, c.dim, c.density).radius;
    }
    row.push_back(front);
    add_band_columns(*sim, c, index, k, row[active_column], act, row);
    add_kicked_columns(*sim, row);
    out.timeseries.add_row(row);
    if (next_snap < spec.snapshot_times.size() &&
        std::abs(spec.snapshot_times[next_snap] - t) <= 1e-12 * std::max(1.0, t)) {
      sim->snapshot(s);
      out.snapshots.push_back(measure_snapshot(spec, s));
      out.snapshots.back().t = spec.snapshot_times[next_snap];
      if (on_snapshot) on_snapshot(index, s);
      ++next_snap;
    }
  }
  GS_CHECK(next_snap == spec.snapshot_times.size());
  return true;
}

std::vector<RealisationFile> realisation_files(const Realisation& r) {
  Table dist, scalars;
  std::size_t rows = 0;
  for (const auto& m : r.snapshots) rows += m.radius.bins();
  for (const auto& n : kDistributionColumns) dist.add_column(n, std::vector<double>(rows));
  for (const auto& n : kScalarColumns) scalars.add_column(n, {});
  std::size_t first = 0;
  for (const auto& m : r.snapshots) {
    const std::size_t bins = m.radius.bins();
    GS_CHECK(m.speed.bins() == bins && m.packing.bins() == bins && m.profile.count.size() == bins);
    for (std::size_t b = 0; b < bins; ++b) {
      dist.column("t")[first + b] = m.t;
      dist.column("bin")[first + b] = double(b);
      dist.column("profile_count")[first + b] = double(m.profile.count[b]);
      dist.column("profile_density")[first + b] = m.profile.density[b];
      dist.column("profile_speed_sum")[first + b] = m.profile.speed_sum[b];
      dist.column("profile_radial_velocity_sum")[first + b] = m.profile.radial_velocity_sum[b];
      dist.column("pressure")[first + b] =
          m.pressure.empty() ? std::numeric_limits<double>::quiet_NaN() : m.pressure[b];
    }
    put_histogram(dist, first, m.radius, "R");
    put_histogram(dist, first, m.speed, "v");
    put_histogram(dist, first, m.packing, "packing");
    first += bins;
    const std::vector<double> row = {m.t,
                                     double(m.radius.samples),
                                     double(m.radius.outside),
                                     double(m.speed.samples),
                                     double(m.speed.outside),
                                     double(m.packing.samples),
                                     double(m.packing.outside),
                                     m.band.typical,
                                     m.band.upper,
                                     m.band.mean,
                                     m.band.cell_side,
                                     m.inner.correlation,
                                     m.inner.median_radius,
                                     m.inner.inner_speed,
                                     m.inner.outer_speed,
                                     m.inner.ratio,
                                     m.measures.front.radius,
                                     m.measures.front.peak_density,
                                     m.measures.densest_cell,
                                     m.measures.local_median,
                                     m.measures.local_upper,
                                     m.measures.cell_small,
                                     m.measures.cell_large,
                                     m.measures.voronoi_median};
    scalars.add_row(row);
  }
  return {{kRealisationFiles[0], to_csv(r.timeseries)},
          {kRealisationFiles[1], to_csv(dist)},
          {kRealisationFiles[2], to_csv(scalars)},
          {kRealisationFiles[3], std::string(kRealisationFormat) + "\n"}};
}

Realisation parse_realisation(const std::vector<RealisationFile>& files, std::uint64_t index,
                              const std::filesystem::path& dir) {
  auto table = [&](const char* name) {
    for (const auto& f : files)
      if (f.name == name) return parse_csv(f.text, (dir / name).string());
    throw UserError((dir / name).string() + ": missing");
  };
  check_format(files, dir);
  Realisation r;
  r.index = index;
  r.timeseries = table(kRealisationFiles[0]);
  // One line naming the file when a column is missing (a folder edited or cut by hand: the
  // format file says which columns a folder of this build has).
  auto need = [&](const Table& t, const char* file, std::string_view column) {
    if (!t.has(column))
      throw UserError((dir / file).string() + ": no column '" + std::string(column) + "'");
  };
  for (const char* n : kAddedColumns) need(r.timeseries, kRealisationFiles[0], n);
  const Table dist = table(kRealisationFiles[1]);
  const Table sc = table(kRealisationFiles[2]);
  for (const auto& n : kDistributionColumns) need(dist, kRealisationFiles[1], n);
  for (const auto& n : kScalarColumns) need(sc, kRealisationFiles[2], n);
  const auto& t = dist.column("t");
  std::size_t first = 0;
  for (std::size_t k = 0; k < sc.rows(); ++k) {
    const double tk = sc.column("t")[k];
    std::size_t bins = 0;
    while (first + bins < t.size() && t[first + bins] == tk) ++bins;
    if (bins < 1)
      throw UserError((dir / "distributions.csv").string() +
                      ": no rows for t = " + format_number(tk));
    SnapshotMeasures m;
    m.t = tk;
    auto s = [&](const char* name) { return sc.column(name)[k]; };
    m.radius = get_histogram(dist, first, bins, "R", s("R_samples"), s("R_outside"));
    m.speed = get_histogram(dist, first, bins, "v", s("v_samples"), s("v_outside"));
    m.packing =
        get_histogram(dist, first, bins, "packing", s("packing_samples"), s("packing_outside"));
    m.profile.edges = m.radius.edges;
    for (std::size_t b = 0; b < bins; ++b) {
      const double n = dist.column("profile_count")[first + b];
      const double ss = dist.column("profile_speed_sum")[first + b];
      const double rs = dist.column("profile_radial_velocity_sum")[first + b];
      m.profile.count.push_back(static_cast<std::uint64_t>(n));
      m.profile.density.push_back(dist.column("profile_density")[first + b]);
      m.profile.speed_sum.push_back(ss);
      m.profile.radial_velocity_sum.push_back(rs);
      const double nan = std::numeric_limits<double>::quiet_NaN();
      m.profile.mean_speed.push_back(n > 0 ? ss / n : nan);
      m.profile.mean_radial_velocity.push_back(n > 0 ? rs / n : nan);
      // NaN: no front at this snapshot, so no pressure profile.
      if (!std::isnan(dist.column("pressure")[first]))
        m.pressure.push_back(dist.column("pressure")[first + b]);
    }
    m.band.typical = s("packing_typical");
    m.band.upper = s("packing_upper");
    m.band.mean = s("packing_mean");
    m.band.cell_side = s("packing_cell_side");
    m.inner.correlation = s("inner_correlation");
    m.inner.median_radius = s("inner_median_radius");
    m.inner.inner_speed = s("inner_speed");
    m.inner.outer_speed = s("outer_speed");
    m.inner.ratio = s("inner_outer_ratio");
    m.measures.front.radius = s("front_radius");
    m.measures.front.peak_density = s("shell_peak_density");
    m.measures.densest_cell = s("packing_densest_cell");
    m.measures.local_median = s("packing_local_median");
    m.measures.local_upper = s("packing_local_upper");
    m.measures.cell_small = s("packing_cell5");
    m.measures.cell_large = s("packing_cell20");
    m.measures.voronoi_median = s("packing_voronoi_median");
    r.snapshots.push_back(std::move(m));
    first += bins;
  }
  if (first != t.size())
    throw UserError((dir / "distributions.csv").string() +
                    ": rows do not match snapshot_scalars.csv");
  return r;
}

void write_realisation(const std::filesystem::path& dir,
                       const std::vector<RealisationFile>& files) {
  namespace fs = std::filesystem;
  const fs::path tmp = temporary_realisation(dir);
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) throw UserError("cannot create '" + tmp.string() + "': " + ec.message());
  for (const auto& f : files) {
    std::ofstream out(tmp / f.name, std::ios::binary | std::ios::trunc);
    out.write(f.text.data(), static_cast<std::streamsize>(f.text.size()));
    out.close();
    if (!out) {
      fs::remove_all(tmp, ec);
      throw UserError("cannot write '" + (dir / f.name).string() + "'");
    }
  }
  fs::rename(tmp, dir, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove_all(tmp, ec);
    throw UserError("cannot write '" + dir.string() + "': " + why);
  }
}

std::filesystem::path temporary_realisation(const std::filesystem::path& dir) {
  std::string name = ".";  // appended, not "." + ...: GCC 12 warns falsely about the latter
  name += dir.filename().string();
  name += ".tmp.";
  name += std::to_string(::getpid());
  return dir.parent_path() / name;
}

Realisation read_realisation(const std::filesystem::path& dir, std::uint64_t index) {
  std::vector<RealisationFile> files;
  for (const char* name : kRealisationFiles) {
    // A folder of a build before the format file: refused by check_format, not "cannot read".
    if (std::string_view(name) == kRealisationFiles[3] && !std::filesystem::exists(dir / name))
      continue;
    files.push_back({name, read_text(dir / name)});
  }
  return parse_realisation(files, index, dir);
}

}  // namespace gs
