// grainshock.Simulation: one realisation's engine (sim/engine.h) with the physics flags' names,
// defaults and validation (sim/config.h). run_until releases the GIL and runs in chunks of
// simulated time sized to ~30 ms of wall time, checking for Ctrl-C between them, so a notebook
// can stop it and keep the simulation at the last chunk's end.
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "io/simulation_file.h"
#include "python/py_module.h"
#include "sim/config.h"
#include "sim/engine.h"
#include "sim/error.h"

namespace gs::py {
namespace {

class PySimulation {
 public:
  explicit PySimulation(std::unique_ptr<Simulation> sim) : sim_(std::move(sim)) {}

  // Another thread may call in while run_until has let go of the GIL: refuse rather than race.
  class Use {
   public:
    explicit Use(PySimulation& s) : s_(s) {
      if (s_.busy_.exchange(true))
        throw std::runtime_error("the Simulation is running in another thread");
    }
    ~Use() { s_.busy_ = false; }
    Use(const Use&) = delete;
    Use& operator=(const Use&) = delete;

   private:
    PySimulation& s_;
  };

  Simulation& sim() { return *sim_; }

  void run_until(double t) {
    Use use(*this);
    if (!std::isfinite(t) || t < sim_->time())
      throw UserError("run_until: t = " + std::to_string(t) + " is before the simulation's time " +
                      std::to_string(sim_->time()));
    using clock = std::chrono::steady_clock;
    constexpr double kChunkSeconds = 0.03;
    while (sim_->time() < t) {
      const double target = std::min(t, sim_->time() + chunk_);
      const auto start = clock::now();
      {
        pb::gil_scoped_release release;
        sim_->run_until(target);
      }
      if (PyErr_CheckSignals() != 0) throw pb::error_already_set();
      const double wall = std::chrono::duration<double>(clock::now() - start).count();
      // Events per unit time grow as the band fills: keep each chunk near kChunkSeconds.
      if (target < t) chunk_ *= std::clamp(kChunkSeconds / std::max(wall, 1e-6), 0.25, 4.0);
    }
  }

 private:
  std::unique_ptr<Simulation> sim_;
  std::atomic<bool> busy_{false};
  double chunk_ = 1;  // simulated time per chunk, adapted as it runs
};

}  // namespace

PhysicsConfig physics(int dim, pb::object particles, double density, double restitution,
                      double cutoff, double speed, std::uint64_t seed, std::uint64_t realisation,
                      const std::string& initial, const std::string& kick_site, double temperature,
                      double lattice, double t_max, const std::optional<std::string>& medium) {
  PhysicsConfig c;
  c.dim = dim;
  // 2e6 is accepted as the flag accepts it, when it is a whole number.
  const double n = particles.cast<double>();
  if (!(std::floor(n) == n && std::fabs(n) < 9.2e18))
    throw UserError("--particles: " + pb::str(particles).cast<std::string>() +
                    " is not a whole number");
  c.particles = static_cast<std::int64_t>(n);
  c.density = density;
  c.restitution = restitution;
  c.cutoff = cutoff;
  c.speed = speed;
  c.seed = seed;
  c.realisation = realisation;
  c.initial = parse_initial(initial);
  c.kick_site = parse_kick_site(kick_site);
  c.temperature = temperature;
  c.lattice = lattice;
  c.t_max = t_max;
  // None: the command line's default, unbounded for kicks in 2D and 3D (default_medium).
  c.medium = medium ? parse_medium(*medium) : default_medium(c);
  validate(c);
  check_memory(c);
  return c;
}

PhysicsConfig physics(const pb::kwargs& kw) {
  const PhysicsConfig d;
  auto get = [&](const char* key, auto fallback) {
    return kw.contains(key) ? kw[key].cast<decltype(fallback)>() : fallback;
  };
  for (auto [key, value] : kw) {
    static const std::set<std::string> known = {
        "dim", "particles", "density", "restitution", "cutoff", "speed", "seed", "realisation",
        "initial", "kick_site", "temperature", "lattice", "t_max", "medium"};
    if (!known.contains(pb::str(key).cast<std::string>()))
      throw pb::type_error("unexpected keyword argument '" + pb::str(key).cast<std::string>() +
                           "'");
  }
  return physics(get("dim", d.dim), kw.contains("particles") ? pb::object(kw["particles"])
                                                             : pb::cast(d.particles),
                 get("density", d.density), get("restitution", d.restitution),
                 get("cutoff", d.cutoff), get("speed", d.speed), get("seed", d.seed),
                 get("realisation", d.realisation), get("initial", std::string("kick")),
                 get("kick_site", std::string("random")), get("temperature", d.temperature),
                 get("lattice", d.lattice), get("t_max", d.t_max),
                 get("medium", std::optional<std::string>()));
}

namespace {

pb::dict config_dict(const PhysicsConfig& c) {
  pb::dict d;
  d["dim"] = c.dim;
  d["particles"] = c.particles;
  d["density"] = c.density;
  d["restitution"] = c.restitution;
  d["cutoff"] = c.cutoff;
  d["speed"] = c.speed;
  d["seed"] = c.seed;
  d["realisation"] = c.realisation;
  d["initial"] = to_string(c.initial);
  d["kick_site"] = to_string(c.kick_site);
  d["temperature"] = c.temperature;
  d["lattice"] = c.lattice;
  d["t_max"] = c.t_max;
  d["medium"] = to_string(c.medium);
  d["box"] = c.box();
  return d;
}

pb::dict sample_dict(const Simulation& sim) {
  const Sample s = sim.sample();
  pb::dict d;
  d["t"] = s.t;
  d["t_paper"] = sim.config().paper_time(s.t);
  d["active"] = s.active;
  d["energy"] = s.energy;
  d["radius_rms"] = s.radius_rms;
  d["speed_rms"] = s.speed_rms;
  d["anisotropy"] = s.anisotropy;
  d["momentum"] = pb::array_t<double>(sim.dim(), s.momentum.data());
  d["collisions"] = s.collisions;
  d["events"] = s.events;
  return d;
}

}  // namespace

void bind_simulation(pb::module_& m) {
  const PhysicsConfig def;
  pb::class_<PySimulation>(m, "Simulation", R"(One realisation of the kicked granular gas.

The arguments are the physics flags of `grainshock run` with the same names (dashes become
underscores), defaults (the paper's) and checks: a bad value raises ValueError with the command
line's one-line message. medium=None is the command's default: "unbounded" for kicks in 2D and
3D (the gas at rest made where the front arrives, `particles` the most it may make), "box"
otherwise; medium="box" gives the periodic box of `particles`, made at once (random sequential
addition), so a large box takes a moment.

    sim = grainshock.Simulation(dim=2, particles=20000, restitution=0.1, seed=3)
    sim.run_until(1000)
    snap = sim.snapshot())")
      .def(pb::init([](int dim, pb::object particles, double density, double restitution,
                       double cutoff, double speed, std::uint64_t seed, std::uint64_t realisation,
                       const std::string& initial, const std::string& kick_site,
                       double temperature, double lattice, double t_max,
                       const std::optional<std::string>& medium) {
             const PhysicsConfig c = physics(dim, particles, density, restitution, cutoff, speed,
                                             seed, realisation, initial, kick_site, temperature,
                                             lattice, t_max, medium);
             std::unique_ptr<Simulation> sim;
             {
               pb::gil_scoped_release release;
               sim = make_simulation(c);
             }
             return std::make_unique<PySimulation>(std::move(sim));
           }),
           pb::kw_only(), pb::arg("dim") = def.dim, pb::arg("particles") = def.particles,
           pb::arg("density") = def.density, pb::arg("restitution") = def.restitution,
           pb::arg("cutoff") = def.cutoff, pb::arg("speed") = def.speed,
           pb::arg("seed") = def.seed, pb::arg("realisation") = def.realisation,
           pb::arg("initial") = "kick", pb::arg("kick_site") = "random",
           pb::arg("temperature") = def.temperature, pb::arg("lattice") = def.lattice,
           pb::arg("t_max") = def.t_max, pb::arg("medium") = pb::none())
      .def("run_until", &PySimulation::run_until, pb::arg("t"),
           R"(Processes every event up to time t (units of diameter / v0) and leaves the clock there.

Releases the GIL (other Python threads run meanwhile); Ctrl-C raises KeyboardInterrupt between
chunks of events, leaving a valid simulation at the time reached.)")
      .def(
          "snapshot",
          [](PySimulation& s, bool active_only) {
            PySimulation::Use use(s);
            auto snap = std::make_shared<Snapshot>();
            {
              pb::gil_scoped_release release;
              if (active_only)
                s.sim().active_snapshot(*snap);
              else
                s.sim().snapshot(*snap);
            }
            return snap;
          },
          pb::arg("active_only") = true,
          "The state now as a Snapshot (a copy: it does not change when the simulation goes on); "
          "active_only keeps the particles that have collided")
      .def_property_readonly("time", [](PySimulation& s) { return s.sim().time(); },
                             "simulation time (diameter / v0)")
      .def_property_readonly(
          "paper_time",
          [](PySimulation& s) { return s.sim().config().paper_time(s.sim().time()); },
          "time in the paper's unit 1/(v0 n^(1/d))")
      .def_property_readonly("collisions",
                             [](PySimulation& s) { return s.sim().stats().collisions; },
                             "velocity-changing collisions so far")
      .def_property_readonly("events", [](PySimulation& s) { return s.sim().stats().events; },
                             "events processed so far (collisions, cell crossings, stale ones)")
      .def_property_readonly("dim", [](PySimulation& s) { return s.sim().dim(); })
      .def_property_readonly("config", [](PySimulation& s) { return config_dict(s.sim().config()); },
                             "the physics as a dict of the flags' names")
      .def(
          "sample",
          [](PySimulation& s) {
            PySimulation::Use use(s);
            return sample_dict(s.sim());
          },
          "One row of timeseries.csv now: t, t_paper, active (N_t), energy (E_t), radius_rms "
          "(R_t), speed_rms (v_t), anisotropy, momentum, collisions, events")
      .def(
          "save",
          [](PySimulation& s, const std::filesystem::path& path) {
            PySimulation::Use use(s);
            pb::gil_scoped_release release;
            save_simulation(s.sim(), path);
          },
          pb::arg("path"),
          "Writes the whole state to a checkpoint file (atomically); Simulation.load continues it "
          "event for event")
      .def_static(
          "load",
          [](const std::filesystem::path& path) {
            std::unique_ptr<Simulation> sim;
            {
              pb::gil_scoped_release release;
              sim = load_simulation_file(path);
            }
            return std::make_unique<PySimulation>(std::move(sim));
          },
          pb::arg("path"), "The Simulation saved in `path` by save()")
      .def("__repr__", [](PySimulation& s) {
        const auto& c = s.sim().config();
        return "<grainshock.Simulation dim=" + std::to_string(c.dim) +
               " particles=" + std::to_string(c.particles) +
               " time=" + pb::repr(pb::float_(s.sim().time())).cast<std::string>() +
               " collisions=" + std::to_string(s.sim().stats().collisions) + ">";
      });
}

}  // namespace gs::py
