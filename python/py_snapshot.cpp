// grainshock.Snapshot: the state at one instant (sim/snapshot.h), from the engine, from any file
// `render` reads (io/snapshot_file.h) or from numpy arrays. Immutable from Python: its arrays are
// read-only views into the C++ vectors that keep the Snapshot alive, so a snapshot stays valid
// and unchanged whatever the simulation that made it does next.
#include <memory>
#include <string>

#include "io/snapshot_file.h"
#include "python/py_module.h"
#include "sim/error.h"
#include "sim/snapshot.h"

namespace gs::py {
namespace {

using Vec3 = Eigen::Vector3d;
static_assert(sizeof(Vec3) == 3 * sizeof(double));

// Positions and velocities are stored with three components; the view shows the first `dim`.
pb::object vectors(const std::vector<Vec3>& v, int dim, pb::handle owner) {
  return view(v.empty() ? nullptr : v.front().data(),
              {static_cast<pb::ssize_t>(v.size()), dim}, {sizeof(Vec3), sizeof(double)}, owner);
}

template <class T>
pb::object column(const std::vector<T>& v, pb::handle owner) {
  return view(v.data(), {static_cast<pb::ssize_t>(v.size())}, {sizeof(T)}, owner);
}

std::vector<Vec3> vectors_from(const pb::handle& obj, const char* name, std::size_t n, int* k) {
  auto a = pb::array_t<double, pb::array::c_style | pb::array::forcecast>::ensure(obj);
  if (!a || a.ndim() != 2 || a.shape(1) < 1 || a.shape(1) > 3 ||
      (n != std::size_t(-1) && std::size_t(a.shape(0)) != n))
    throw UserError(std::string("Snapshot.from_arrays: ") + name +
                    " must be an (N, d) array of numbers with d = 1, 2 or 3" +
                    (n != std::size_t(-1) ? ", N = " + std::to_string(n) : ""));
  *k = static_cast<int>(a.shape(1));
  std::vector<Vec3> out(static_cast<std::size_t>(a.shape(0)), Vec3::Zero());
  auto r = a.unchecked<2>();
  for (pb::ssize_t i = 0; i < a.shape(0); ++i)
    for (int j = 0; j < *k; ++j) out[i][j] = r(i, j);
  return out;
}

template <class T>
std::vector<T> values_from(const pb::handle& obj, const char* name, std::size_t n) {
  auto a = pb::array_t<T, pb::array::c_style | pb::array::forcecast>::ensure(obj);
  if (!a || a.ndim() != 1 || std::size_t(a.shape(0)) != n)
    throw UserError(std::string("Snapshot.from_arrays: ") + name + " must have " +
                    std::to_string(n) + " values, one per particle");
  return std::vector<T>(a.data(), a.data() + n);
}

std::shared_ptr<Snapshot> from_arrays(const pb::object& positions, const pb::object& velocities,
                                      const pb::object& radius, const pb::object& active,
                                      const pb::object& first_collision, const pb::object& box,
                                      const pb::object& time, int dim, const pb::dict& columns) {
  auto s = std::make_shared<Snapshot>();
  int k = 0;
  s->position = vectors_from(positions, "positions", std::size_t(-1), &k);
  const std::size_t n = s->size();
  int kv = 0;
  if (!velocities.is_none()) s->velocity = vectors_from(velocities, "velocities", n, &kv);
  if (!radius.is_none()) s->radius = values_from<double>(radius, "radius", n);
  if (!active.is_none()) s->active = values_from<std::uint8_t>(active, "active", n);
  if (!first_collision.is_none())
    s->first_collision = values_from<double>(first_collision, "first_collision", n);
  for (auto [name, values] : columns)
    s->columns.push_back({pb::str(name), values_from<double>(values, "a column", n)});
  s->info.dim = dim > 0 ? dim : k;
  if (!box.is_none()) {
    const auto b = values_from<double>(box, "box", static_cast<std::size_t>(s->info.dim));
    for (int j = 0; j < s->info.dim; ++j) s->info.box[j] = b[j];
  }
  s->info.has_time = !time.is_none();
  if (s->info.has_time) s->info.time = time.cast<double>();
  ReadOptions options;
  options.dim = dim;
  finish_snapshot(*s, options, "Snapshot.from_arrays");
  return s;
}

std::shared_ptr<Snapshot> read(const std::filesystem::path& where, long frame, int dim, double dt,
                               bool unwrap) {
  const std::string path = where.string();
  ReadOptions options;
  options.dim = dim;
  options.dt = dt;
  options.unwrap = unwrap;
  const SnapshotFile file = open_snapshots(path, options);
  const long count = static_cast<long>(file.frame_count());
  // Negative frames count from the end, as Python's indices do; read() names a frame too large.
  const long k = frame < 0 ? frame + count : frame;
  if (k < 0)
    throw UserError(path + ": frame " + std::to_string(frame) + " of a file of " +
                    std::to_string(count) + " frames");
  return std::make_shared<Snapshot>(file.read(static_cast<std::size_t>(k)));
}

}  // namespace

void bind_snapshot(pb::module_& m) {
  pb::class_<Snapshot, std::shared_ptr<Snapshot>>(m, "Snapshot", R"(The particles at one instant.

Made by Simulation.snapshot(), grainshock.read(path) or Snapshot.from_arrays(...). Its arrays
are read-only numpy views of the snapshot's own memory (no copy); they keep it alive, and it
never changes after it is made.)")
      .def_property_readonly(
          "positions",
          [](pb::object self) {
            const auto& s = self.cast<const Snapshot&>();
            return vectors(s.position, s.info.dim, self);
          },
          "(N, dim) float64: unwrapped positions")
      .def_property_readonly(
          "velocities",
          [](pb::object self) -> pb::object {
            const auto& s = self.cast<const Snapshot&>();
            if (s.velocity.empty() && s.size() > 0) return pb::none();
            return vectors(s.velocity, s.info.dim, self);
          },
          "(N, dim) float64, or None when the file had no velocities")
      .def_property_readonly(
          "radius", [](pb::object self) { return column(self.cast<const Snapshot&>().radius, self); },
          "(N,) float64: radii (0.5 for the engine's unit-diameter spheres)")
      .def_property_readonly(
          "active",
          [](pb::object self) {
            const auto& a = self.cast<const Snapshot&>().active;
            return view(reinterpret_cast<const bool*>(a.data()),
                        {static_cast<pb::ssize_t>(a.size())}, {1}, self);
          },
          "(N,) bool: has collided at least once (all True when the file does not say)")
      .def_property_readonly(
          "first_collision",
          [](pb::object self) -> pb::object {
            const auto& s = self.cast<const Snapshot&>();
            if (s.first_collision.empty()) return pb::none();
            return column(s.first_collision, self);
          },
          "(N,) float64: time of the first collision (-1: never), or None")
      .def_property_readonly(
          "columns",
          [](pb::object self) {
            pb::dict d;
            for (const auto& c : self.cast<const Snapshot&>().columns)
              d[pb::str(c.name)] = column(c.values, self);
            return d;
          },
          "dict of the file's further numeric per-particle columns, name -> (N,) float64")
      .def_property_readonly(
          "box",
          [](const Snapshot& s) {
            return pb::array_t<double>(s.info.dim, s.info.box.data());
          },
          "(dim,) float64: edges of the periodic box (zeros when unknown)")
      .def_property_readonly(
          "origin",
          [](const Snapshot& s) {
            return pb::array_t<double>(s.info.dim, s.info.origin.data());
          },
          "(dim,) float64: lower corner of the box")
      .def_property_readonly("dim", [](const Snapshot& s) { return s.info.dim; }, "1, 2 or 3")
      .def_property_readonly("time", [](const Snapshot& s) { return s.info.time; },
                             "simulation time (diameter / v0); 0 when the file gives none")
      .def_property_readonly(
          "step", [](const Snapshot& s) -> pb::object {
            return s.info.step ? pb::cast(*s.info.step) : pb::none();
          },
          "time step of LAMMPS/HOOMD files, collisions for ours, or None")
      .def_property_readonly("notes", [](const Snapshot& s) { return s.notes; },
                             "what the reader assumed where the file says nothing")
      .def("__len__", &Snapshot::size)
      .def("__repr__",
           [](const Snapshot& s) {
             return "<grainshock.Snapshot dim=" + std::to_string(s.info.dim) +
                    " particles=" + std::to_string(s.size()) +
                    " time=" + pb::repr(pb::float_(s.info.time)).cast<std::string>() + ">";
           })
      .def_static("from_arrays", &from_arrays, pb::arg("positions"), pb::kw_only(),
                  pb::arg("velocities") = pb::none(), pb::arg("radius") = pb::none(),
                  pb::arg("active") = pb::none(), pb::arg("first_collision") = pb::none(),
                  pb::arg("box") = pb::none(), pb::arg("time") = pb::none(),
                  pb::arg("dim") = 0, pb::arg("columns") = pb::dict(),
                  R"(A snapshot of your own arrays (copied), completed as the file readers do.

positions: (N, d) with d = 1, 2 or 3; velocities (N, d) optional; radius (default 0.5),
active (default all True), first_collision: (N,); box: (dim,) edges; time: float;
dim: the dimension if not d; columns: dict name -> (N,) extra values to colour by.)");

  m.def("read", &read, pb::arg("path"), pb::arg("frame") = -1, pb::kw_only(), pb::arg("dim") = 0,
        pb::arg("dt") = 0.0, pb::arg("unwrap") = false,
        R"(Frame `frame` (default the last; negative counts from the end) of a snapshot file.

Every format `grainshock render` reads, told by content: extended XYZ (ours, ASE, OVITO),
LAMMPS text dumps, HOOMD GSD. dim overrides the file's dimension; dt gives a time to files
with steps only; unwrap unwraps LAMMPS/GSD positions. A bad file raises ValueError.)");
  m.def("frame_count",
        [](const std::filesystem::path& path) { return open_snapshots(path.string()).frame_count(); },
        pb::arg("path"), "Number of frames in a snapshot file");
}

}  // namespace gs::py
