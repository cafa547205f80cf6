#include "sim/config.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "sim/error.h"
#include "sim/format.h"
#include "sim/memory_budget.h"
#include "sim/unbounded_medium.h"

namespace gs {

double PhysicsConfig::box() const {
  // Exact: an integer under 2^15 times a 21-bit fraction. CellGrid then finds this many cells of
  // exactly kUnboundedCellSide.
  if (unbounded()) return unbounded_cells_per_side(*this) * kUnboundedCellSide;
  const double n = lattice > 0 ? 1.0 / lattice : density;
  return std::pow(static_cast<double>(particles) / n, 1.0 / dim);
}

double PhysicsConfig::paper_time(double t) const {
  const double n = lattice > 0 ? 1.0 / lattice : density;
  return t * speed * std::pow(n, 1.0 / dim);
}

// 2D: up to 32766^2 cells (even, under 2^15); 3D: up to 1288^3, whose whole tiles of 4^3
// (sim/cell_grid.h) number under 2^31 (1D: validate refuses).
static double most_unbounded_cells_per_side(int dim) { return dim == 3 ? 1288 : 32766; }

int unbounded_cells_per_side(const PhysicsConfig& c) {
  const double most = most_unbounded_cells_per_side(c.dim);
  const double side = std::pow(static_cast<double>(c.particles) / c.density, 1.0 / c.dim);
  return 2 * static_cast<int>(std::clamp(std::ceil(2 * side / kUnboundedCellSide), 8.0, most / 2));
}

double min_unbounded_density(int dim) {
  // The region make_cell (sim/engine.cpp) may fill: all but the outermost cell on each side.
  const double radius = (most_unbounded_cells_per_side(dim) / 2 - 1) * kUnboundedCellSide;
  const double swept = dim == 3 ? std::numbers::pi : 2.0;  // area (volume) swept per unit length
  constexpr double kFreePaths = 10;
  const double least = kFreePaths / (swept * radius);
  // Rounded up to two digits, so that the message names a value the check accepts.
  const double unit = std::pow(10.0, std::floor(std::log10(least)) - 1);
  return std::ceil(least / unit) * unit;
}

double max_rsa_density(int dim) {
  // A little under the jamming densities (1D: Renyi 0.7476; 2D: 0.547 * 4/pi = 0.697;
  // 3D: 0.384 * 6/pi = 0.733), where the last particles still find room quickly.
  switch (dim) {
    case 1:
      return 0.74;
    case 2:
      return 0.69;
    default:
      return 0.73;
  }
}

std::int64_t lattice_side(std::int64_t n, int dim) {
  const auto power = [dim](std::int64_t k) {
    std::int64_t p = 1;
    for (int d = 0; d < dim; ++d) p *= k;
    return p;
  };
  auto k = static_cast<std::int64_t>(std::ceil(std::pow(static_cast<double>(n), 1.0 / dim)));
  while (power(k) < n) ++k;
  while (k > 1 && power(k - 1) >= n) --k;
  return k;
}

double max_thermal_density(int dim, std::int64_t n) {
  if (dim == 1) return max_rsa_density(1);
  const double fluid = dim == 2 ? 0.70 * 4 / std::numbers::pi : 0.52 * 6 / std::numbers::pi;
  const double side = 1.001 * static_cast<double>(lattice_side(n, dim));
  const double lattice = std::min(fluid, static_cast<double>(n) / std::pow(side, dim));
  return std::max(max_rsa_density(dim), lattice);
}

static std::string num(double x) {
  return format_double(x);
}

// A size in a message, to three significant digits: "537000 GB", not "536999.936380992 GB".
static std::string rounded(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

void validate(const PhysicsConfig& c) {
  // A value outside its flag's range is a usage error; settings that cannot work together
  // (further down) are user errors.
  auto bad = [](const std::string& m) { throw UsageError(m); };
  auto fail = [](const std::string& m) { throw UserError(m); };
  if (c.dim < 1 || c.dim > 3) bad("--dim " + std::to_string(c.dim) + ": must be 1, 2 or 3");
  if (c.particles < 2)
    bad("--particles " + std::to_string(c.particles) + ": need at least 2 particles");
  // Particle indices are 32-bit in the engine.
  if (c.particles >= INT32_MAX)
    bad("--particles " + std::to_string(c.particles) + ": at most " +
         std::to_string(INT32_MAX - 1) + " (and this many would need about " +
         rounded(estimated_bytes(c) / 1e9) + " GB of memory)");
  // Run files are TOML, whose integers are signed 64-bit: a larger seed could not be read back.
  if (c.seed > static_cast<std::uint64_t>(INT64_MAX))
    bad("--seed " + std::to_string(c.seed) + ": must be in [0, " + std::to_string(INT64_MAX) +
         "]");
  if (c.realisation > static_cast<std::uint64_t>(INT64_MAX))
    bad("--realisation " + std::to_string(c.realisation) + ": must be in [0, " +
         std::to_string(INT64_MAX) + "]");
  if (c.unbounded()) {
    if (c.dim == 1) bad("--medium unbounded: exists only in 2D and 3D (--dim 2 or 3)");
    if (c.initial != Initial::Kick) bad("--medium unbounded: only for --initial kick");
    if (c.lattice != 0.0) bad("--medium unbounded: not with --lattice");
  }
  if (c.lattice != 0.0) {
    if (c.dim != 1) bad("--lattice: a lattice start exists only in 1D (--dim 1)");
    if (!(c.lattice > 1.0) || !std::isfinite(c.lattice))
      bad("--lattice " + num(c.lattice) + ": spacing must exceed the diameter 1");
  } else {
    if (!(c.density > 0)) bad("--density " + num(c.density) + ": must be positive");
    // Limits of the physics, not of the flag.
    if (c.initial == Initial::Kick && c.density > max_rsa_density(c.dim))
      fail("--density " + num(c.density) + ": above " + num(max_rsa_density(c.dim)) +
           ", the most random sequential addition reaches in " + std::to_string(c.dim) + "D");
    if (c.initial == Initial::Thermal && c.density > max_thermal_density(c.dim, c.particles))
      fail("--density " + num(c.density) + ": above " +
           num(max_thermal_density(c.dim, c.particles)) + ", the most a thermal start of " +
           std::to_string(c.particles) + " particles reaches in " + std::to_string(c.dim) + "D");
  }
  if (!(c.restitution >= 0 && c.restitution <= 1))
    bad("--restitution " + num(c.restitution) + ": must lie in [0, 1]");
  if (!(c.cutoff >= 0) || !std::isfinite(c.cutoff))
    bad("--cutoff " + num(c.cutoff) + ": must be finite and >= 0");
  if (!(c.speed > 0) || !std::isfinite(c.speed))
    bad("--speed " + num(c.speed) + ": must be positive");
  if (!(c.t_max > 0) || !std::isfinite(c.t_max))
    bad("--t-max " + num(c.t_max) + ": must be positive");
  if (c.initial == Initial::Thermal && !(c.temperature > 0 && std::isfinite(c.temperature)))
    bad("--temperature " + num(c.temperature) + ": must be positive");
  if (c.unbounded()) {
    // The box's limits below do not apply; the medium's calibration has its own (it names
    // --density).
    medium_candidate_density(c.dim, c.density);
    if (c.density < min_unbounded_density(c.dim))
      fail("--density " + num(c.density) + ": under " + rounded(min_unbounded_density(c.dim)) +
           ", the least the unbounded medium takes in " + std::to_string(c.dim) +
           "D (the kicked particle's mean free path must be under a tenth of the medium's "
           "reach); use --density " + rounded(min_unbounded_density(c.dim)) +
           " or more");
    return;
  }
  // Below three diameters a particle could meet its own periodic image within the cell stencil.
  if (c.box() < 3.0)
    fail("--particles " + std::to_string(c.particles) + ": box side " + num(c.box()) +
         " is under 3 diameters; use more particles");
  // The engine keeps a particle's cell coordinates in 16 bits, beside its next event.
  if (c.dim > 1 && c.box() > 32767)
    fail("--density " + num(c.density) + ": box side " + num(c.box()) +
         " is over 32767 diameters in " + std::to_string(c.dim) + "D; use a higher density");
  const double n = static_cast<double>(c.particles);
  const double cells = std::pow(std::floor(c.box() / (1.0 + 1e-9)), c.dim);
  const double limit = std::max(kMinCellLimit, kCellsPerParticle * n);
  if (cells > limit) {
    const std::string what = std::to_string(c.particles) + " particles in a box of side " +
                             num(c.box()) + " need " + num(cells) + " neighbour cells (" +
                             rounded(cells * 8 / 1e9) + " GB), over the limit of " + num(limit);
    if (c.lattice > 0)
      fail("--lattice " + num(c.lattice) + ": " + what + "; use --lattice " +
           num(std::floor(limit / n)) + " or less");
    fail("--density " + num(c.density) + ": " + what + "; use --density " +
         num(n / limit * 1.0001) + " or more");
  }
  check_memory(c, 0);
}

Medium default_medium(const PhysicsConfig& c) {
  const bool kick = c.initial == Initial::Kick && c.dim > 1 && c.lattice == 0.0;
  return kick ? Medium::Unbounded : Medium::Box;
}

namespace {

// The engine's records (sim/engine.h) and queue entry, and a snapshot with its extended-XYZ text.
double engine_bytes(int dim) { return 64 + 32 + 16 + 8 + 4 + 4.0 * dim + 8 + 4 + 8; }
constexpr double kSnapshotBytes = 65 + 140;

// The unbounded medium's cells per made particle: a made cell's list head (4 B) and its place in
// the list of made cells (4 B), about 2/n cells per particle with the shell beyond the front.
double unbounded_cell_bytes(const PhysicsConfig& c) {
  return 2.0 / (c.density * std::pow(kUnboundedCellSide, c.dim)) * 8;
}

}  // namespace

double unbounded_bytes_per_particle(const PhysicsConfig& c) {
  return engine_bytes(c.dim) + unbounded_cell_bytes(c) + kSnapshotBytes;
}

double estimated_bytes(const PhysicsConfig& c, int snapshot_copies) {
  const double engine = engine_bytes(c.dim), snapshot = kSnapshotBytes;
  if (c.unbounded()) {
    // At most N particles made, with no initial state, and the medium's memo of candidates
    // (cleared at kMemoCandidates, sim/engine.h).
    return static_cast<double>(c.particles) *
               (engine + unbounded_cell_bytes(c) + snapshot * snapshot_copies) +
           (1 << 20) * 48.0;
  }
  // Random sequential addition's centres, links and cell heads, and a kick's resting store
  // (sim/resting_store.h), whose slots stay when their particles become records.
  const double initial = 8.0 * c.dim + 20 + 8.0 * c.dim + 12;
  const double cells = std::pow(std::floor(c.box() / (1.0 + 1e-9)), c.dim);
  return static_cast<double>(c.particles) * (engine + initial + snapshot * snapshot_copies) +
         8 * cells;
}

void check_memory(const PhysicsConfig& c, int snapshot_copies) {
  if (c.unbounded()) return;
  const double have = physical_memory_bytes();
  const double need = estimated_bytes(c, snapshot_copies);
  if (have > 0 && need > have) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "--particles %lld: needs about %.3g GB of memory, this machine has %.3g GB",
                  static_cast<long long>(c.particles), need / 1e9, have / 1e9);
    throw UserError(text);
  }
}

const char* to_string(Initial i) {
  return i == Initial::Kick ? "kick" : "thermal";
}
const char* to_string(KickSite k) {
  return k == KickSite::Random ? "random" : "centre";
}
const char* to_string(Medium m) {
  return m == Medium::Box ? "box" : "unbounded";
}

Initial parse_initial(const std::string& word) {
  if (word != "kick" && word != "thermal")
    throw UserError("--initial: '" + word + "' is not kick or thermal");
  return word == "kick" ? Initial::Kick : Initial::Thermal;
}
KickSite parse_kick_site(const std::string& word) {
  if (word != "random" && word != "centre")
    throw UserError("--kick-site: '" + word + "' is not random or centre");
  return word == "random" ? KickSite::Random : KickSite::Centre;
}

Medium parse_medium(const std::string& word) {
  if (word != "box" && word != "unbounded")
    throw UserError("--medium: '" + word + "' is not box or unbounded");
  return word == "box" ? Medium::Box : Medium::Unbounded;
}

std::string to_toml(const PhysicsConfig& c) {
  std::ostringstream o;
  o << "dim = " << c.dim << "\n";
  o << "particles = " << c.particles << "\n";
  o << "density = " << num(c.density) << "\n";
  o << "restitution = " << num(c.restitution) << "\n";
  o << "cutoff = " << num(c.cutoff) << "\n";
  o << "speed = " << num(c.speed) << "\n";
  o << "seed = " << c.seed << "\n";
  o << "realisation = " << c.realisation << "\n";
  o << "t-max = " << num(c.t_max) << "\n";
  o << "initial = \"" << to_string(c.initial) << "\"\n";
  o << "kick-site = \"" << to_string(c.kick_site) << "\"\n";
  o << "temperature = " << num(c.temperature) << "\n";
  o << "lattice = " << num(c.lattice) << "\n";
  // Box runs write no key, so that their run.toml and checkpoints (which hold these lines) stay
  // those of the runs made before the medium existed, and resume.
  if (c.unbounded()) o << "medium = \"" << to_string(c.medium) << "\"\n";
  return o.str();
}

std::string physics_toml(const PhysicsConfig& c) {
  return c.unbounded() ? to_toml(c) : to_toml(c) + "medium = \"box\"\n";
}

}  // namespace gs
