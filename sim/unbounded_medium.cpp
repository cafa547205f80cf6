#include "sim/unbounded_medium.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <string>

#include "sim/error.h"
#include "sim/rng.h"

namespace gs {

namespace {

// Candidate densities rho against number density n = 0.01 k (k = 0, 1, ...), measured with
// bench/calibrate_medium.cpp (2D: `calibrate_medium 1024 128 12 4.5 3.5`, 12 regions of 1024^2;
// 3D: `calibrate_medium 64 128 8 4.5 6`, 8 regions of 128^3): for each k, the arrival time by
// which a region of the medium drawn at a larger rho holds n per unit volume, times that rho,
// averaged over the regions. The relative standard errors of the entries, below, are well
// under the tests' sampling error.
constexpr double kRho2[] = {0.0, 0.010166, 0.020620, 0.031459, 0.042653, 0.054231,
  0.066275, 0.078630, 0.091502, 0.104819, 0.118738, 0.133109,
  0.148042, 0.163590, 0.179875, 0.196858, 0.214547, 0.233004,
  0.252450, 0.272675, 0.293994, 0.316320, 0.339914, 0.364725,
  0.390619, 0.418242, 0.447332, 0.478204, 0.510999, 0.545642,
  0.582738, 0.622083, 0.664365, 0.709812, 0.758516, 0.811080,
  0.867580, 0.928866, 0.995924, 1.068635, 1.148788, 1.236531,
  1.333071, 1.441029, 1.560854, 1.695027, 1.845780, 2.016132,
  2.210784, 2.435209, 2.694904};
// n = 0.05 1.4e-3, 0.10 7.9e-4, 0.15 5.9e-4, 0.20 7.4e-4, 0.25 6.1e-4, 0.30 4.5e-4, 0.35 5.2e-4,
// 0.40 4.5e-4, 0.45 4.9e-4, 0.50 7.8e-4
constexpr double kRho3[] = {0.0, 0.010194, 0.020860, 0.031995, 0.043609, 0.055798,
  0.068578, 0.081992, 0.096012, 0.110747, 0.126286, 0.142579,
  0.159822, 0.178035, 0.197244, 0.217588, 0.239189, 0.262164,
  0.286475, 0.312312, 0.339891, 0.369401, 0.400887, 0.434731,
  0.471186, 0.510475, 0.552921, 0.598743, 0.648351, 0.702262,
  0.761229, 0.825446, 0.895780, 0.972822, 1.057871, 1.152195,
  1.256481, 1.372707, 1.502914, 1.648558, 1.812824, 1.998529,
  2.211674, 2.454955, 2.733548, 3.056377, 3.433289, 3.873905,
  4.392979, 5.014611, 5.755807};
// n = 0.05 1.4e-3, 0.10 9.2e-4, 0.15 8.6e-4, 0.20 8.2e-4, 0.25 7.2e-4, 0.30 6.5e-4, 0.35 5.7e-4,
// 0.40 5.7e-4, 0.45 4.6e-4, 0.50 9.8e-4

// Ein(s) = integral_0^s (1 - e^-u) / u du: its series up to s = 1, Simpson's rule beyond.
double ein_series(double s) {
  double term = 1.0, sum = 0.0;  // sum_k (-1)^(k+1) s^k / (k k!)
  for (int k = 1; k < 30; ++k) {
    term *= s / k;
    sum += (k % 2 ? term : -term) / k;
  }
  return sum;
}

double ein(double s) {
  if (s <= 1.0) return ein_series(s);
  const int m = 2 * static_cast<int>(std::ceil(64 * s));
  const double h = (s - 1.0) / m;
  auto f = [](double u) { return (1.0 - std::exp(-u)) / u; };
  double sum = f(1.0) + f(s);
  for (int i = 1; i < m; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(1.0 + i * h);
  return ein_series(1.0) + sum * h / 3.0;
}

double interpolate(const double* rho, int count, double density) {
  // ln(rho / n) is smooth and nearly linear in n (it is v n / 2 + O(n^2)): interpolate that.
  const double k = density / 0.01;
  const int i = std::min(static_cast<int>(k), count - 2);
  const double w = k - i;
  auto f = [&](int j) { return j == 0 ? 0.0 : std::log(rho[j] / (0.01 * j)); };
  return density * std::exp((1 - w) * f(i) + w * f(i + 1));
}

}  // namespace

double renyi_density(double rho) {
  // theta(rho) = integral_0^rho exp(-2 Ein(s)) ds, Simpson's rule on a fine grid.
  if (rho <= 0) return 0;
  const int m = 2 * static_cast<int>(std::ceil(200 * rho));
  const double h = rho / m;
  auto f = [](double s) { return std::exp(-2.0 * ein(s)); };
  double sum = f(0.0) + f(rho);
  for (int i = 1; i < m; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(i * h);
  return sum * h / 3.0;
}

double medium_max_density(int dim) {
  switch (dim) {
    case 1: return 0.70;
    case 2: return 0.01 * (static_cast<int>(std::size(kRho2)) - 1);
    case 3: return 0.01 * (static_cast<int>(std::size(kRho3)) - 1);
    default: GS_CHECK_MSG(false, "dimension must be 1, 2 or 3");
  }
}

double medium_candidate_density(int dim, double density) {
  const double top = medium_max_density(dim);
  if (!(density > 0) || density > top)
    throw UserError("--density: the unbounded medium in " + std::to_string(dim) +
                    "D is calibrated for densities in (0, " + std::to_string(top) + "], not " +
                    std::to_string(density));
  if (dim == 1) {
    // Newton on theta(rho) = density; theta' = exp(-2 Ein(rho)), theta concave: converges from
    // below, starting at rho = density.
    double rho = density;
    for (int it = 0; it < 100; ++it) {
      const double step = (density - renyi_density(rho)) / std::exp(-2.0 * ein(rho));
      rho += step;
      if (std::abs(step) < 1e-13 * rho) break;
    }
    return rho;
  }
  if (dim == 2) return interpolate(kRho2, static_cast<int>(std::size(kRho2)), density);
  return interpolate(kRho3, static_cast<int>(std::size(kRho3)), density);
}

template <int D>
UnboundedMedium<D>::UnboundedMedium(const MediumOptions& o)
    : UnboundedMedium(medium_candidate_density(o.dim, o.density), o.cell_side, o.seed,
                      o.realisation) {
  GS_CHECK(o.dim == D);
}

template <int D>
UnboundedMedium<D>::UnboundedMedium(double candidate_density, double cell_side,
                                    std::uint64_t seed, std::uint64_t realisation)
    : rho_(candidate_density),
      side_(cell_side),
      medium_seed_(seed, realisation, Stream::Medium) {
  if (!(cell_side >= 1.0) || !(cell_side <= 16.0))
    throw UserError("medium cell side: must be in [1, 16] diameters, not " +
                    std::to_string(cell_side));
  GS_CHECK(candidate_density > 0 && std::isfinite(candidate_density));
  // A cell's count is Poisson(mu) drawn by inversion, in pieces of mean at most 8 so that e^-mu
  // stays far from underflow; every cell has the same pieces.
  const double mu = rho_ * std::pow(side_, D);
  for (double left = mu; left > 0; left -= 8.0) {
    const double m = std::min(left, 8.0);
    pieces_.push_back({m, std::exp(-m)});
  }
}

template <int D>
std::size_t UnboundedMedium<D>::CellHash::operator()(const Cell& c) const {
  std::uint64_t h = 0x9E3779B97F4A7C15ULL;
  for (const std::int64_t k : c) {
    h ^= static_cast<std::uint64_t>(k) + 0x9E3779B97F4A7C15ULL + (h << 6) + (h >> 2);
    h *= 0xBF58476D1CE4E5B9ULL;
    h ^= h >> 31;
  }
  return static_cast<std::size_t>(h);
}

template <int D>
bool UnboundedMedium<D>::earlier(const Candidate& a, const Candidate& b) {
  if (a.t != b.t) return a.t < b.t;
  // Equal 53-bit times (about once in 2^53 pairs) are ordered by position, so that the order
  // stays a function of the candidates themselves.
  for (int k = 0; k < D; ++k)
    if (a.x[k] != b.x[k]) return a.x[k] < b.x[k];
  return false;
}

// A cell's key mixes in x, then y, then z (Rng's keyed constructor), so the cells of a block share
// the mixing of all but their last coordinate: it is done here once per row, not once per cell,
// and each cell's stream is the one the keyed constructor gives. Level k (x, then x and y) is
// built in place from level k - 1, downwards, so that each entry is read before it is replaced.
template <int D>
void UnboundedMedium<D>::seed_rows(const Cell& block) {
  row_seeds_[0] = medium_seed_;
  int width = 1;
  for (int k = 0; k + 1 < D; ++k, width *= kBlock)
    for (int i = width * kBlock - 1; i >= 0; --i)
      row_seeds_[static_cast<std::size_t>(i)] =
          row_seeds_[static_cast<std::size_t>(i % width)].then(block[k] * kBlock + i / width);
}

template <int D>
void UnboundedMedium<D>::draw_block(const Cell& block) {
  const Block entry{static_cast<std::uint32_t>(pool_.size()),
                    static_cast<std::uint32_t>(offsets_.size())};
  seed_rows(block);
  constexpr int kRows = kBlockCells / kBlock;
  Cell local{};
  for (int n = 0; n < kBlockCells; ++n) {
    Cell c;
    for (int k = 0; k < D; ++k) c[k] = block[k] * kBlock + local[k];
    offsets_.push_back(static_cast<std::uint32_t>(pool_.size() - entry.first_candidate));
    Rng rng(row_seeds_[static_cast<std::size_t>(n % kRows)].then(c[D - 1]));
    std::uint64_t count = 0;
    for (const Piece& piece : pieces_) {
      const double m = piece.mean;
      double p = piece.p0, cdf = p;
      const double u = rng.uniform();
      std::uint64_t k = 0;
      while (u >= cdf && k < 1000) {
        ++k;
        p *= m / static_cast<double>(k);
        cdf += p;
      }
      count += k;
    }
    GS_CHECK(pool_.size() + count < std::numeric_limits<std::uint32_t>::max());
    for (std::uint64_t i = 0; i < count; ++i) {
      Candidate cand;
      for (int k = 0; k < D; ++k) {
        const double lo = static_cast<double>(c[k]) * side_;
        const double hi = static_cast<double>(c[k] + 1) * side_;
        // Rounding may put lo + u s on hi: keep every centre inside its own half-open cell.
        const double x = lo + rng.uniform() * side_;
        cand.x[k] = x < hi ? x : std::nextafter(hi, lo);
      }
      cand.t = rng.uniform();
      cand.state = 0;
      pool_.push_back(cand);
    }
    int k = 0;
    while (k < D && local[k] == kBlock - 1) local[k] = 0, ++k;
    if (k < D) ++local[k];
  }
  offsets_.push_back(static_cast<std::uint32_t>(pool_.size() - entry.first_candidate));
  blocks_.emplace(block, entry);
}

template <int D>
const typename UnboundedMedium<D>::Block& UnboundedMedium<D>::block(const Cell& b) {
  int slot = 0;
  for (int k = 0; k < D; ++k) slot |= static_cast<int>(b[k] & 3) << (2 * k);
  Recent& r = recent_[static_cast<std::size_t>(slot)];
  if (!r.valid || r.key != b) {
    auto it = blocks_.find(b);
    if (it == blocks_.end()) {
      draw_block(b);
      it = blocks_.find(b);
    }
    r = {b, it->second, true};
  }
  return r.block;
}

template <int D>
typename UnboundedMedium<D>::Range UnboundedMedium<D>::cell(const Cell& c) {
  Cell b;
  int local = 0;
  for (int k = D - 1; k >= 0; --k) {
    b[k] = c[k] >> kShift;  // floor division: cell -1 is in block -1
    local = (local << kShift) | static_cast<int>(c[k] & (kBlock - 1));
  }
  const Block& entry = block(b);
  const std::uint32_t* o = &offsets_[entry.first_offset + static_cast<std::uint32_t>(local)];
  return {entry.first_candidate + o[0], o[1] - o[0]};
}

template <int D>
void UnboundedMedium<D>::gather(const Cell& lo, const Cell& hi) {
  if (stencil_valid_ && lo == stencil_lo_ && hi == stencil_hi_) return;
  // The cells span one block or two along each axis (at most 3 cells of blocks 4 or more wide):
  // each of those blocks is found (drawn if need be) once, before any offset is read, since
  // drawing grows the pool and the offsets. They are numbered by a bit per axis, set for the
  // upper one.
  Cell first, last;
  for (int k = 0; k < D; ++k) first[k] = lo[k] >> kShift, last[k] = hi[k] >> kShift;
  std::array<Block, 1 << D> blocks{};
  for (int m = 0; m < (1 << D); ++m) {
    Cell b;
    bool used = true;
    for (int k = 0; k < D; ++k) {
      used = used && (!((m >> k) & 1) || last[k] != first[k]);
      b[k] = (m >> k) & 1 ? last[k] : first[k];
    }
    if (used) blocks[static_cast<std::size_t>(m)] = block(b);
  }
  // What each coordinate adds to a cell's place: its block's bit and its index in the block. A
  // row along x within one block is consecutive in it: one range holds its candidates.
  int bits[D][3], locals[D][3], counts[D];
  for (int k = 1; k < D; ++k) {
    counts[k] = static_cast<int>(hi[k] - lo[k] + 1);
    for (int a = 0; a < counts[k]; ++a) {
      const std::int64_t c = lo[k] + a;
      bits[k][a] = static_cast<int>((c >> kShift) != first[k]) << k;
      locals[k][a] = static_cast<int>(c & (kBlock - 1)) << (kShift * k);
    }
  }
  int seg_bit[2], seg_local[2], seg_cells[2], segs = 0;
  for (std::int64_t x = lo[0]; x <= hi[0]; ++segs) {
    const bool upper = (x >> kShift) != first[0];
    const std::int64_t end = upper ? hi[0] : std::min(hi[0], (first[0] + 1) * kBlock - 1);
    seg_bit[segs] = upper;
    seg_local[segs] = static_cast<int>(x & (kBlock - 1));
    seg_cells[segs] = static_cast<int>(end - x + 1);
    x = end + 1;
  }
  int n = 0;
  int at[D] = {};
  for (;;) {
    int m = 0, local = 0;
    for (int k = 1; k < D; ++k) m |= bits[k][at[k]], local |= locals[k][at[k]];
    for (int g = 0; g < segs; ++g) {
      const Block& b = blocks[static_cast<std::size_t>(m | seg_bit[g])];
      const std::uint32_t* o =
          &offsets_[b.first_offset + static_cast<std::uint32_t>(local | seg_local[g])];
      stencil_[static_cast<std::size_t>(n++)] = {b.first_candidate + o[0], o[seg_cells[g]] - o[0]};
    }
    int k = 1;
    while (k < D && at[k] == counts[k] - 1) at[k] = 0, ++k;
    if (k >= D) break;
    ++at[k];
  }
  stencil_lo_ = lo;
  stencil_hi_ = hi;
  stencil_count_ = n;
  stencil_valid_ = true;
}

template <int D>
bool UnboundedMedium<D>::accepted(std::uint32_t start) {
  if (pool_[start].state != 0) return pool_[start].state > 0;
  stack_.assign(1, start);
  while (!stack_.empty()) {
    const std::uint32_t j = stack_.back();
    if (pool_[j].state != 0) {
      stack_.pop_back();
      continue;
    }
    // The cells any candidate within one diameter can lie in (2 or 3 per axis, as s >= 1).
    const Vec<D> x = pool_[j].x;
    Cell lo, hi;
    for (int k = 0; k < D; ++k) {
      lo[k] = static_cast<std::int64_t>(std::floor((x[k] - 1.0) / side_));
      hi[k] = static_cast<std::int64_t>(std::floor((x[k] + 1.0) / side_));
    }
    gather(lo, hi);
    const Candidate& me = pool_[j];
    bool blocked = false;
    nearby_.clear();
    for (int r = 0; r < stencil_count_ && !blocked; ++r) {
      const Range range = stencil_[static_cast<std::size_t>(r)];
      for (std::uint32_t i = range.first; i < range.first + range.count; ++i) {
        const Candidate& other = pool_[i];
        if (other.state < 0 || !earlier(other, me) || (other.x - x).squaredNorm() >= 1.0)
          continue;
        if (other.state > 0) {
          blocked = true;
          break;
        }
        nearby_.push_back(i);
      }
    }
    if (blocked) {
      pool_[j].state = -1;
      stack_.pop_back();
    } else if (nearby_.empty()) {
      pool_[j].state = 1;
      stack_.pop_back();
    } else {
      // Decide the earlier ones first; this one is looked at again once they are known.
      stack_.insert(stack_.end(), nearby_.begin(), nearby_.end());
    }
  }
  return pool_[start].state > 0;
}

template <int D>
void UnboundedMedium<D>::particles(const Cell& c, VecArray<D>& out) {
  const Range r = cell(c);
  for (std::uint32_t i = r.first; i < r.first + r.count; ++i)
    if (accepted(i)) out.push_back(pool_[i].x);
}

template <int D>
void UnboundedMedium<D>::particles(const Cell& c, VecArray<D>& out,
                                   std::vector<double>& arrival) {
  const Range r = cell(c);
  for (std::uint32_t i = r.first; i < r.first + r.count; ++i)
    if (accepted(i)) {
      out.push_back(pool_[i].x);
      arrival.push_back(pool_[i].t);
    }
}

template <int D>
std::size_t UnboundedMedium<D>::memory_bytes() const {
  // A node of the cell table holds its key, value and next pointer (libstdc++ also caches the
  // hash); the buckets are one pointer each.
  const std::size_t node = sizeof(Cell) + sizeof(Block) + 2 * sizeof(void*);
  return pool_.capacity() * sizeof(Candidate) + offsets_.capacity() * sizeof(std::uint32_t) +
         blocks_.size() * node + blocks_.bucket_count() * sizeof(void*);
}

template <int D>
void UnboundedMedium<D>::clear() {
  pool_ = {};
  offsets_ = {};
  blocks_ = {};
  recent_ = {};
  stencil_valid_ = false;
}

template class UnboundedMedium<1>;
template class UnboundedMedium<2>;
template class UnboundedMedium<3>;

}  // namespace gs
