// Bytes per particle of the engine: at rest, and the extra of a moving one; and
// the unbounded medium against the box: cost per collision and peak memory.
// Each measurement runs in a child process of its own, because a process's peak resident set
// only grows: the parent reads the child's peak from wait4, the child sends what it holds after
// construction and after the run (VmRSS) through a pipe. And the size and cost of a long
// realisation's state in flight (analysis/realisation_in_flight.h), measured in this process.
#include <malloc.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "analysis/realisation_in_flight.h"
#include "bench/bench.h"
#include "jobs/figures_plan.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/recorder.h"

namespace gs::bench {
namespace {

// Resident bytes of this process now.
double resident_bytes() {
  std::ifstream f("/proc/self/statm");
  double pages_total = 0, pages_resident = 0;
  f >> pages_total >> pages_resident;
  return pages_resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

struct Footprint {
  double peak = 0;         // bytes, the child's whole life (construction's transients included)
  double constructed = 0;  // bytes held once the engine is made
  double after_run = 0;    // bytes held at t_max
  double active = 0;       // particles that have moved by t_max
  double made = 0;         // particles the engine holds at t_max
  double collisions = 0, events = 0;
  double run_cpu = 0;   // CPU-seconds of run_until
  double run_wall = 0;  // wall seconds of run_until
};

PhysicsConfig kick_at(int dim, std::int64_t n, double t_max) {
  PhysicsConfig c;
  c.dim = dim;
  c.particles = n;
  c.restitution = 0.8;
  c.t_max = t_max;
  return c;
}

// The kick of `c` run to its t_max, measured in a child. `pages_alone`: without transparent
// huge pages, so that the resident set counts the bytes touched to 4 kB.
Footprint kick_footprint(const PhysicsConfig& c, bool pages_alone = false) {
  int fd[2];
  GS_CHECK(pipe(fd) == 0);
  const pid_t pid = fork();
  GS_CHECK(pid >= 0);
  if (pid == 0) {
    close(fd[0]);
    // Every large block mapped and unmapped on its own, whatever N: glibc's default threshold
    // adapts to earlier frees, so N and 2N would put the same arrays on the heap or not.
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    if (pages_alone && prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0) != 0) _exit(1);
    validate(c);
    auto sim = make_simulation(c);
    Footprint f;
    f.constructed = resident_bytes();
    const double cpu0 = cpu_seconds(), wall0 = wall_seconds();
    sim->run_until(c.t_max);
    f.run_cpu = cpu_seconds() - cpu0;
    f.run_wall = wall_seconds() - wall0;
    f.after_run = resident_bytes();
    f.active = static_cast<double>(sim->sample().active);
    f.made = static_cast<double>(sim->particle_count());
    f.collisions = static_cast<double>(sim->stats().collisions);
    f.events = static_cast<double>(sim->stats().events);
    const bool sent = write(fd[1], &f, sizeof f) == static_cast<ssize_t>(sizeof f);
    _exit(sent ? 0 : 1);
  }
  close(fd[1]);
  Footprint f;
  const bool got = read(fd[0], &f, sizeof f) == static_cast<ssize_t>(sizeof f);
  close(fd[0]);
  int status = 0;
  rusage ru{};
  GS_CHECK(wait4(pid, &status, 0, &ru) == pid);
  if (!got || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw UserError("bench: the measuring child process failed");
  f.peak = static_cast<double>(ru.ru_maxrss) * 1024.0;
  return f;
}

// At rest: the difference between N and 2N after the same kick (the blast is the same size, so
// the extra particles are all at rest). Moving: that, plus the growth of the 2N run's resident
// set from its construction to t_max per particle that started moving in between. Both in
// children without huge pages, whose rounding of each array up to 2 MB is a cost per array, not
// per particle (with them, about 50 B a moving sphere at 1.4e5 of them).
std::vector<Figure> bytes_per_particle(int dim, std::int64_t n, double t_max) {
  const Footprint one = kick_footprint(kick_at(dim, n, t_max), true);
  const Footprint two = kick_footprint(kick_at(dim, 2 * n, t_max), true);
  const auto per_rest = [&](double Footprint::*m) {
    return (two.*m - one.*m) / static_cast<double>(n);
  };
  return {{"bytes_per_resting_particle_peak", per_rest(&Footprint::peak), "B", "<= 40"},
          {"bytes_per_resting_particle_held", per_rest(&Footprint::constructed), "B", "<= 40"},
          {"bytes_per_resting_particle_at_t_max", per_rest(&Footprint::after_run), "B", ""},
          {"bytes_per_moving_particle",
           per_rest(&Footprint::constructed) +
               (two.after_run - two.constructed) / std::max(1.0, two.active),
           "B", "<= 160"},
          {"moving_particles", two.active, "", ""}};
}

// The same r = 0.8 kick (same seed statistics, not the same gas) in a box of n particles and in
// the unbounded medium, to a time at which the box's front is still far from its edge, so that
// both have about the same N_t: CPU time per collision and per event of run_until (the medium's
// making included, the box's random sequential addition not) and peak resident memory. One
// realisation's cost per collision varies by 10-20% with its history (sim/kick3d_scaling), so
// the costs are summed over `realisations` of each. The medium may make up to n particles.
std::vector<Figure> unbounded_against_box(int dim, std::int64_t n, double t_max, int realisations) {
  struct Sum {
    double active = 0, cpu = 0, collisions = 0, events = 0, peak = 0, made = 0;
  } box, open;
  for (int k = 0; k < realisations; ++k) {
    PhysicsConfig c = kick_at(dim, n, t_max);
    c.kick_site = KickSite::Centre;
    c.realisation = static_cast<std::uint64_t>(k);
    for (Sum* sum : {&box, &open}) {
      c.medium = sum == &box ? Medium::Box : Medium::Unbounded;
      const Footprint f = kick_footprint(c);
      sum->active += f.active / realisations;
      sum->cpu += f.run_cpu;
      sum->collisions += f.collisions;
      sum->events += f.events;
      sum->peak = std::max(sum->peak, f.peak);
      sum->made += f.made / realisations;
    }
  }
  const auto per = [](const Sum& s, double Sum::*what) { return 1e6 * s.cpu / (s.*what); };
  return {{"box_active_mean", box.active, "", ""},
          {"unbounded_active_mean", open.active, "", ""},
          {"box_cpu_microseconds_per_collision", per(box, &Sum::collisions), "us", ""},
          {"unbounded_cpu_microseconds_per_collision", per(open, &Sum::collisions), "us", ""},
          {"unbounded_over_box_cost_per_collision",
           per(open, &Sum::collisions) / per(box, &Sum::collisions), "", ""},
          {"unbounded_over_box_cost_per_event", per(open, &Sum::events) / per(box, &Sum::events),
           "", ""},
          {"box_peak_megabytes", box.peak / 1e6, "MB", ""},
          {"unbounded_peak_megabytes", open.peak / 1e6, "MB", ""},
          {"unbounded_particles_made_mean", open.made, "", ""}};
}

// `figures --limit`'s 3D r = 0.9 case (its physics and cap on made particles), from the plan.
jobs::FigureCase limit_3d_r09() {
  const jobs::FiguresPlan plan = jobs::figures_plan(jobs::FiguresMode::Full, 1, false, true);
  for (const auto& c : plan.cases) {
    const PhysicsConfig& p = c.spec.physics;
    if (c.role == jobs::CaseRole::Limit && p.dim == 3 && p.restitution == 0.9) return c;
  }
  throw UserError("bench: the --limit plan has no 3D r = 0.9 case");
}

// One realisation of that case run to the time its E_t slope is expected to plateau: what each
// of its realisations spends before its plateau window starts. Measured (t = 3.5e5, load ~3):
// 272 s wall and CPU, 2.35e5 collisions per CPU-second, 2.24e6 active and 2.35e6 made, peak
// 934 MB (398 B per made sphere, the engine's estimate 425).
std::vector<Figure> kick_to_plateau() {
  const jobs::FigureCase c = limit_3d_r09();
  PhysicsConfig run = c.spec.physics;
  run.t_max = c.plateau_start;
  const Footprint f = kick_footprint(run);
  return {{"t_max", run.t_max, "", ""},
          {"peak_megabytes", f.peak / 1e6, "MB", ""},
          {"wall_seconds", f.run_wall, "s", ""},
          {"cpu_seconds", f.run_cpu, "s", ""},
          {"collisions_per_cpu_second", f.collisions / f.run_cpu, "1/s", ""},
          {"active", f.active, "", ""},
          {"particles_made", f.made, "", ""},
          {"peak_bytes_per_made_particle", f.peak / std::max(1.0, f.made), "B", ""}};
}

// The state in flight (analysis/realisation_in_flight.h) of one realisation of that case at
// t = 1e5: its size and the seconds to write it (synced, renamed) and read it back, what a
// realisation of `figures --limit` pays every --checkpoint-minutes. The measures so far it
// holds are a few kB of text; the engine is the rest.
std::vector<Figure> in_flight_3d() {
  const jobs::FigureCase c = limit_3d_r09();
  const EnsembleSpec& spec = c.spec;
  const std::uint64_t index = spec.physics.realisation;
  auto sim = make_simulation(spec.physics);
  const double c0 = cpu_seconds();
  sim->run_until(1e5);
  const double run_cpu = cpu_seconds() - c0;
  Recorder recorder(spec.physics);
  Realisation partial = empty_realisation(recorder, index);
  const auto file = std::filesystem::temp_directory_path() /
                    ("grainshock_bench_in_flight_" + std::to_string(::getpid()));
  const double w0 = wall_seconds();
  save_in_flight(file, spec, index, 0, *sim, recorder, partial);
  const double write = wall_seconds() - w0;
  const double bytes = static_cast<double>(std::filesystem::file_size(file));
  const double made = static_cast<double>(sim->particle_count());
  sim.reset();
  std::size_t next = 0;
  const double r0 = wall_seconds();
  const auto loaded = load_in_flight(file, spec, index, recorder, partial, next);
  const double read = wall_seconds() - r0;
  remove_in_flight(file);
  return {{"t", 1e5, "", ""},
          {"run_cpu_seconds", run_cpu, "s", ""},
          {"particles_made", made, "", ""},
          {"state_megabytes", bytes / 1e6, "MB", ""},
          {"state_bytes_per_made_particle", bytes / std::max(1.0, made), "B", ""},
          {"write_seconds", write, "s", "small against --checkpoint-minutes"},
          {"read_seconds", read, "s", ""}};
}

}  // namespace

void add_memory_cases(std::vector<Case>& cases) {
  cases.push_back({"sim/bytes_per_particle_2d",
                   "resident bytes per particle, 2D r = 0.8 kick to t = 3e5, N = 1e6 and 2e6",
                   false, [] { return bytes_per_particle(2, 1000000, 300000); }});
  cases.push_back({"sim/bytes_per_particle_3d",
                   "resident bytes per particle, 3D r = 0.8 kick to t = 3e4, N = 1e6 and 2e6",
                   false, [] { return bytes_per_particle(3, 1000000, 30000); }});
  // Box side 2000: at t = 3e4 the outermost active disc is about 200 from the kick.
  cases.push_back(
      {"sim/unbounded_vs_box_2d",
       "2D r = 0.8 kick to t = 3e4, 4 realisations: box of 1e6 discs against the unbounded medium",
       false, [] { return unbounded_against_box(2, 1000000, 30000, 4); }});
  // Box side 200: at t = 1e4 the outermost active sphere is about 45 from the kick.
  cases.push_back({"sim/unbounded_vs_box_3d",
                   "3D r = 0.8 kick to t = 1e4, 4 realisations: box of 2e6 spheres against the "
                   "unbounded medium",
                   false, [] { return unbounded_against_box(3, 2000000, 10000, 4); }});
  cases.push_back({"sim/kick3d_r0.9_plateau",
                   "3D r = 0.9 kick of figures --limit in the unbounded medium to the time its "
                   "E_t slope's plateau starts, one realisation",
                   true, kick_to_plateau});
  cases.push_back({"io/in_flight_3d_r0.9",
                   "the state in flight of a 3D r = 0.9 realisation of figures --limit at t = 1e5: "
                   "size, write and read seconds",
                   true, in_flight_3d});
}

}  // namespace gs::bench
