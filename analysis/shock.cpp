#include "analysis/shock.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/error.h"

namespace gs {

double packing_fraction(int dim, double n) {
  return dim == 2 ? std::numbers::pi * n / 4 : std::numbers::pi * n / 6;
}

double hard_sphere_compressibility(int dim, double eta) {
  GS_CHECK(dim == 2 || dim == 3);
  if (dim == 2) return (1 + eta * eta / 8) / ((1 - eta) * (1 - eta));
  return (1 + eta + eta * eta - eta * eta * eta) / std::pow(1 - eta, 3);
}

double strong_shock_compression(int dim, double n0) {
  if (dim != 2 && dim != 3) throw UserError("shock compression: dimension must be 2 or 3");
  const double phi0 = packing_fraction(dim, n0);
  if (!(phi0 > 0 && phi0 < 0.5))
    throw UserError("shock compression: packing fraction must be in (0, 0.5)");
  // g(X) = X - 1 - d / Z(X phi0) increases with X (Z does), from g(1) < 0; bisect on
  // [1, d + 1], where g >= 0 because Z >= 1, kept below close packing of the equation of state.
  double lo = 1, hi = std::min(dim + 1.0, 0.99 / phi0);
  for (int k = 0; k < 100; ++k) {
    const double x = 0.5 * (lo + hi);
    const double g = x - 1 - dim / hard_sphere_compressibility(dim, x * phi0);
    (g < 0 ? lo : hi) = x;
  }
  return 0.5 * (lo + hi);
}

}  // namespace gs
