// Measures the table of candidate densities in sim/unbounded_medium.cpp: for d = 2 and 3, draws
// the medium at a candidate density rho_max over a cube of cells in blocks (the memo dropped
// between blocks: the particles do not depend on it), sorts the accepted particles' arrival
// times, and for each number density n = 0.01 k reads the arrival time tau by which n V particles
// had arrived; that region at candidate density tau rho_max holds exactly n per unit volume.
// Entries are averaged over independent realisations; their standard error is printed.
//   build/bench/calibrate_medium [side2 side3 realisations]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "sim/unbounded_medium.h"

namespace {

template <int D>
std::vector<double> arrivals(double rho_max, int side, int block, std::uint64_t realisation) {
  gs::UnboundedMedium<D> medium(rho_max, 1.0, 20261203, realisation);
  gs::VecArray<D> x;
  std::vector<double> t;
  const int blocks = side / block;
  std::array<int, D> b{};
  for (;;) {
    std::array<std::int64_t, D> c{};
    std::array<int, D> k{};
    for (;;) {
      for (int a = 0; a < D; ++a) c[a] = static_cast<std::int64_t>(b[a]) * block + k[a];
      medium.particles(c, x, t);
      int a = 0;
      while (a < D && k[a] == block - 1) k[a] = 0, ++a;
      if (a == D) break;
      ++k[a];
    }
    medium.clear();
    int a = 0;
    while (a < D && b[a] == blocks - 1) b[a] = 0, ++a;
    if (a == D) break;
    ++b[a];
  }
  std::sort(t.begin(), t.end());
  return t;
}

template <int D>
void table(double rho_max, int side, int block, int realisations, int entries) {
  const double volume = std::pow(static_cast<double>(side / block * block), D);
  std::vector<double> sum(entries, 0.0), sum2(entries, 0.0);
  for (int r = 0; r < realisations; ++r) {
    const auto t = arrivals<D>(rho_max, side, block, static_cast<std::uint64_t>(r));
    std::fprintf(stderr, "%dD realisation %d: %zu particles, density %.5f at rho %.3f\n", D, r,
                 t.size(), static_cast<double>(t.size()) / volume, rho_max);
    for (int k = 1; k < entries; ++k) {
      const auto m = static_cast<std::size_t>(std::llround(0.01 * k * volume));
      if (m == 0 || m > t.size()) {
        std::fprintf(stderr, "rho_max too small for n = %.2f\n", 0.01 * k);
        std::exit(1);
      }
      const double rho = rho_max * t[m - 1];
      sum[k] += rho;
      sum2[k] += rho * rho;
    }
  }
  std::printf("constexpr double kRho%d[] = {0.0", D);
  for (int k = 1; k < entries; ++k) std::printf(",%s%.6f", k % 6 == 0 ? "\n  " : " ", sum[k] / realisations);
  std::printf("};\n// standard error (relative):");
  for (int k = 5; k < entries; k += 5) {
    const double mean = sum[k] / realisations;
    const double var = (sum2[k] / realisations - mean * mean) * realisations / (realisations - 1);
    std::printf(" n=%.2f %.1e", 0.01 * k, std::sqrt(var / realisations) / mean);
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  const int side2 = argc > 1 ? std::atoi(argv[1]) : 1024;
  const int side3 = argc > 2 ? std::atoi(argv[2]) : 128;
  const int realisations = argc > 3 ? std::atoi(argv[3]) : 4;
  // Packing 0.40 in 2D (n = 0.509) and 0.26 in 3D (n = 0.50).
  table<2>(argc > 4 ? std::atof(argv[4]) : 2.0, side2, 64, realisations, 51);
  table<3>(argc > 5 ? std::atof(argv[5]) : 2.0, side3, 32, realisations, 51);
}
