// Bytes per particle of the engine (issue 31 part 2): at rest, and the extra of a moving one.
// Each measurement runs in a child process of its own, because a process's peak resident set
// only grows: the parent reads the child's peak from wait4, the child sends what it holds after
// construction and after the run (VmRSS) through a pipe.
#include <malloc.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "bench/bench.h"
#include "sim/engine.h"
#include "sim/error.h"

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
};

// The r = 0.8 kick of `n` particles run to `t_max`, measured in a child.
Footprint kick_footprint(int dim, std::int64_t n, double t_max) {
  int fd[2];
  GS_CHECK(pipe(fd) == 0);
  const pid_t pid = fork();
  GS_CHECK(pid >= 0);
  if (pid == 0) {
    close(fd[0]);
    // Every large block mapped and unmapped on its own, whatever N: glibc's default threshold
    // adapts to earlier frees, so N and 2N would put the same arrays on the heap or not.
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    PhysicsConfig c;
    c.dim = dim;
    c.particles = n;
    c.restitution = 0.8;
    c.t_max = t_max;
    validate(c);
    auto sim = make_simulation(c);
    Footprint f;
    f.constructed = resident_bytes();
    sim->run_until(t_max);
    f.after_run = resident_bytes();
    f.active = static_cast<double>(sim->sample().active);
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
// the extra particles are all at rest). Moving: that, plus the growth of one run's resident set
// from its construction to t_max per particle that started moving in between (the engine holds
// every particle's whole state from the start, so a particle costs little more when it moves).
std::vector<Figure> bytes_per_particle(int dim, std::int64_t n, double t_max) {
  const Footprint one = kick_footprint(dim, n, t_max);
  const Footprint two = kick_footprint(dim, 2 * n, t_max);
  const auto per_rest = [&](double Footprint::*m) {
    return (two.*m - one.*m) / static_cast<double>(n);
  };
  return {{"bytes_per_resting_particle_peak", per_rest(&Footprint::peak), "B", "<= 40"},
          {"bytes_per_resting_particle_held", per_rest(&Footprint::constructed), "B", "<= 40"},
          {"bytes_per_moving_particle",
           per_rest(&Footprint::constructed) +
               (two.after_run - two.constructed) / std::max(1.0, two.active),
           "B", "<= 160"},
          {"moving_particles", two.active, "", ""}};
}

}  // namespace

void add_memory_cases(std::vector<Case>& cases) {
  cases.push_back({"sim/bytes_per_particle_2d",
                   "resident bytes per particle, 2D r = 0.8 kick to t = 3e4, N = 1e6 and 2e6",
                   false, [] { return bytes_per_particle(2, 1000000, 30000); }});
  cases.push_back({"sim/bytes_per_particle_3d",
                   "resident bytes per particle, 3D r = 0.8 kick to t = 3e4, N = 1e6 and 2e6",
                   false, [] { return bytes_per_particle(3, 1000000, 30000); }});
}

}  // namespace gs::bench
