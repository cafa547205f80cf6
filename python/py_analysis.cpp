// Observables of a snapshot (sim/observables.h) as numbers and numpy arrays: N_t, E_t, R_t, v_t,
// the gyration tensor and anisotropy, P(R,t), P(v,t) and their scaled forms, radial profiles,
// band packing and the inner edge's speed.
#include <memory>

#include "python/py_module.h"
#include "sim/observables.h"

namespace gs::py {
namespace {

pb::dict histogram_dict(const Histogram& h) {
  pb::dict d;
  d["edges"] = copy(h.edges);
  d["values"] = copy(h.values);
  std::vector<double> centres(h.bins());
  for (std::size_t i = 0; i < h.bins(); ++i) centres[i] = h.centre(i);
  d["centres"] = copy(centres);
  d["samples"] = h.samples;
  d["outside"] = h.outside;
  return d;
}

Binning binning(int bins, double lo, double hi) { return Binning{bins, lo, hi}; }

pb::array matrix(const Eigen::Matrix3d& m, int dim) {
  pb::array_t<double> a({dim, dim});
  auto w = a.mutable_unchecked<2>();
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) w(i, j) = m(i, j);
  return a;
}

}  // namespace

void bind_analysis(pb::module_& m) {
  m.def(
      "observables",
      [](const Snapshot& s) {
        Shape sh;
        double energy = 0;
        {
          pb::gil_scoped_release release;
          sh = measure_shape(s);
          energy = kinetic_energy(s);
        }
        const int d = sh.dim;
        pb::dict out;
        out["t"] = s.info.time;
        out["active"] = sh.active;
        out["energy"] = energy;
        out["radius_rms"] = sh.radius_rms;
        out["speed_rms"] = sh.speed_rms;
        out["anisotropy"] = sh.anisotropy;
        out["centre"] = pb::array_t<double>(d, sh.centre.data());
        out["centre_velocity"] = pb::array_t<double>(d, sh.centre_velocity.data());
        out["gyration"] = matrix(sh.gyration, d);
        out["eigenvalues"] = pb::array_t<double>(d, sh.eigenvalues.data());
        return out;
      },
      pb::arg("snapshot"),
      R"(N_t ('active'), E_t ('energy', every particle), R_t ('radius_rms'), v_t ('speed_rms'),
the anisotropy index A, centre of mass, gyration tensor and its eigenvalues, as a dict.

A snapshot of the active particles alone gives the same R_t, v_t and A; E_t counts what the
snapshot holds.)");
  m.def(
      "radial_distribution",
      [](const Snapshot& s, int bins, double lo, double hi) {
        return histogram_dict(radial_distribution(s, binning(bins, lo, hi)));
      },
      pb::arg("snapshot"), pb::kw_only(), pb::arg("bins") = 50, pb::arg("lo") = 0.0,
      pb::arg("hi") = 0.0,
      "P(R,t): distribution of active particles' distances from their centre of mass; dict of "
      "edges, centres, values (density), samples, outside. hi <= lo: [0, max]");
  m.def(
      "speed_distribution",
      [](const Snapshot& s, int bins, double lo, double hi) {
        return histogram_dict(speed_distribution(s, binning(bins, lo, hi)));
      },
      pb::arg("snapshot"), pb::kw_only(), pb::arg("bins") = 50, pb::arg("lo") = 0.0,
      pb::arg("hi") = 0.0, "P(v,t): distribution of active particles' speeds (as above)");
  m.def(
      "scaled_radial_distribution",
      [](const Snapshot& s, double alpha, int bins) {
        return histogram_dict(
            scaled_radial_distribution(radial_distribution(s, binning(bins, 0, 0)), s.info.time,
                                       alpha));
      },
      pb::arg("snapshot"), pb::arg("alpha"), pb::kw_only(), pb::arg("bins") = 50,
      "The paper's Eq. (9): x = R t^-alpha, density t^alpha P(R,t)");
  m.def(
      "scaled_speed_distribution",
      [](const Snapshot& s, double alpha, int bins) {
        return histogram_dict(scaled_speed_distribution(speed_distribution(s, binning(bins, 0, 0)),
                                                        s.info.time, alpha));
      },
      pb::arg("snapshot"), pb::arg("alpha"), pb::kw_only(), pb::arg("bins") = 50,
      "The paper's Eq. (10): x = v t^(1-alpha), density t^(alpha-1) P(v,t)");
  m.def(
      "radial_profile",
      [](const Snapshot& s, int bins) {
        const RadialProfile p = radial_profile(s, binning(bins, 0, 0));
        pb::dict d;
        d["edges"] = copy(p.edges);
        d["count"] = copy(p.count);
        d["density"] = copy(p.density);
        d["mean_speed"] = copy(p.mean_speed);
        d["mean_radial_velocity"] = copy(p.mean_radial_velocity);
        return d;
      },
      pb::arg("snapshot"), pb::kw_only(), pb::arg("bins") = 50,
      "Shells about the active particles' centre of mass: edges, count, density, mean_speed, "
      "mean_radial_velocity (relative to the centre-of-mass velocity), as numpy arrays");
  m.def(
      "band_packing",
      [](const Snapshot& s, double cell, double upper_quantile) {
        PackingOptions o;
        o.cell = cell;
        o.upper_quantile = upper_quantile;
        const BandPacking b = band_packing(s, o);
        pb::dict d;
        d["typical"] = b.typical;
        d["mean"] = b.mean;
        d["mode"] = b.mode;
        d["upper"] = b.upper;
        d["cell_side"] = b.cell_side;
        d["fraction"] = copy(b.fraction);
        d["active"] = copy(b.active);
        d["distribution"] = histogram_dict(b.distribution);
        d["definition"] = BandPacking::definition;
        return d;
      },
      pb::arg("snapshot"), pb::kw_only(), pb::arg("cell") = 10.0,
      pb::arg("upper_quantile") = 0.9,
      "The paper's band packing fraction in cells of side ~cell (needs every particle, not the "
      "active ones alone: take snapshot(active_only=False))");
  m.def(
      "inner_edge_speed",
      [](const Snapshot& s) {
        const InnerEdge e = inner_edge_speed(s);
        pb::dict d;
        d["correlation"] = e.correlation;
        d["median_radius"] = e.median_radius;
        d["inner_speed"] = e.inner_speed;
        d["outer_speed"] = e.outer_speed;
        d["ratio"] = e.ratio;
        return d;
      },
      pb::arg("snapshot"), "Faster particles on the band's inner edge, as numbers");
}

}  // namespace gs::py
