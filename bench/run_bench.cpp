// Benchmarks of `grainshock run` around the engine: the run loop with its samples,
// timeseries.csv and snapshots, and its checkpoints; the Fig. 1 job whole.
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/json.h"
#include "bench/bench.h"
#include "io/checkpoint.h"
#include "jobs/run_job.h"
#include "jobs/run_loop.h"

extern char** environ;

namespace gs::bench {
using jobs::RunLoop;
using jobs::RunPlan;

namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("grainshock_bench_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

RunPlan kick_plan(std::int64_t n) {
  RunPlan plan;  // the defaults of `grainshock run`: 20 samples per decade, a final snapshot
  plan.physics.dim = 3;
  plan.physics.particles = n;
  plan.physics.restitution = 0.5;
  plan.physics.t_max = 2e4;
  return plan;
}

// The run loop of `grainshock run` (jobs/run_loop.h) at N = 2e5 and 2e6: 3D, r = 0.5, to
// t = 2e4, where both blasts are still inside their boxes (sim/kick3d_scaling). Particles at
// rest must cost nothing in the loop either, so the cost per collision should barely grow with
// N. Set-up (the initial state and first checkpoint) is left out, and so is the final snapshot
// (all N particles, timed on its own). The two runs take turns in 20 steps of time, so that both
// meet the same machine (a figure drifts by up to 10% from one minute to the next).
std::vector<Figure> run_scaling() {
  constexpr std::int64_t kSizes[2] = {200000, 2000000};
  std::unique_ptr<RunLoop> loops[2];
  fs::path dirs[2];
  double cpu[2] = {0, 0}, collisions[2] = {0, 0}, last[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    dirs[k] = scratch("run" + std::to_string(k));
    loops[k] = std::make_unique<RunLoop>(kick_plan(kSizes[k]), dirs[k], "bench");
    loops[k]->checkpoint_every = 0;
  }
  constexpr int kSteps = 20;
  for (int step = 1; step < kSteps; ++step)
    for (int k = 0; k < 2; ++k) {
      const double c0 = cpu_seconds();
      loops[k]->run(2e4 * step / kSteps);
      cpu[k] += cpu_seconds() - c0;
      collisions[k] = static_cast<double>(loops[k]->simulation().stats().collisions);
    }
  for (int k = 0; k < 2; ++k) {  // the last step holds the final snapshot
    const double c0 = cpu_seconds();
    loops[k]->run();
    last[k] = cpu_seconds() - c0;
    fs::remove_all(dirs[k]);
  }
  const double small = 1e6 * cpu[0] / collisions[0], large = 1e6 * cpu[1] / collisions[1];
  return {{"cpu_microseconds_per_collision_2e5", small, "us", ""},
          {"cpu_microseconds_per_collision_2e6", large, "us", ""},
          {"collisions_2e6", collisions[1], "", ""},
          {"cost_per_collision_ratio", large / small, "", "<= 1.2"},
          {"last_step_with_final_snapshot_cpu_seconds_2e6", last[1], "s", ""}};
}

// A checkpoint of a 2e6-sphere 3D kick at t = 2e4 (r = 0.5): written and read back.
std::vector<Figure> checkpoint_2e6() {
  const fs::path dir = scratch("checkpoint");
  RunPlan plan = kick_plan(2000000);
  RunLoop loop(plan, dir, "bench");
  loop.checkpoint_every = 0;
  loop.run(plan.physics.t_max * 0.999);
  const double w0 = wall_seconds();
  loop.write_checkpoint();
  const double write = wall_seconds() - w0;
  loop.finish_checkpoint();
  const double durable = wall_seconds() - w0;
  const auto bytes = static_cast<double>(fs::file_size(RunLoop::checkpoint_path(dir)));
  const double r0 = wall_seconds();
  const auto resumed = RunLoop::resume(plan, dir, "bench");
  const double read = wall_seconds() - r0;
  const double same = resumed->simulation().stats().events == loop.simulation().stats().events;
  fs::remove_all(dir);
  // The run waits `write_seconds`; the sync to disk goes on beside it (jobs/run_loop.h).
  return {{"write_seconds", write, "s", "< 1 s"},
          {"on_disk_seconds", durable, "s", ""},
          {"read_seconds", read, "s", "< 1 s"},
          {"megabytes", bytes / 1e6, "MB", ""},
          // One checkpoint per minute costs its write time once a minute.
          {"share_of_run_time_every_60_s", write / 60, "", "< 0.02"},
          {"read_back_same_state", same, "", "1"}};
}

// `grainshock run` with no flags: the Fig. 1 job (2.5e5 discs, r = 0.1, to paper time 50000,
// four snapshots with their pictures and overlay, the elastic comparison, the 240-frame movie
// with its inset), as the command runs it. The figure to watch is timing.json's pictures-and-movie
// time (the movie's share of the run's wall time, then everything after sampling); the job's
// wall and CPU time say what the two cores did in all.
std::vector<Figure> fig1_job() {
  const fs::path dir = scratch("fig1");
  fs::remove_all(dir);
  jobs::RunOptions o;  // the C++ PhysicsConfig's defaults are the paper's box, as the job's are
  jobs::use_fig1_job(o);
  o.out = dir.string();
  o.quiet = true;
  const double w0 = wall_seconds(), c0 = cpu_seconds();
  jobs::run_job(o, false);
  const double wall = wall_seconds() - w0, cpu = cpu_seconds() - c0;
  std::ifstream f(dir / "timing.json");
  const Json t = Json::parse(f);
  fs::remove_all(dir);
  return {
      {"pictures_and_movie_seconds", t["pictures_and_movie_seconds"].get<double>(), "s", "<= 10"},
      {"movie_during_run_seconds", t["movie_during_run_seconds"].get<double>(), "s", ""},
      {"run_seconds", t["run_seconds"].get<double>(), "s", ""},
      {"job_wall_seconds", wall, "s", ""},
      {"job_cpu_seconds", cpu, "s", ""},
      {"load_average_1min", load_average(), "", ""}};
}

// Peak resident bytes of the whole command `grainshock run --dim 3 --particles N --restitution
// 0.5 --t-max 1 --medium box --snapshot-particles active`, as a user measures it (the child's
// ru_maxrss from wait4, with the machine's huge-page setting); 0 if it failed.
double run_command_peak(std::int64_t n) {
  const fs::path dir = scratch("peak" + std::to_string(n));
  fs::remove_all(dir);
  std::vector<std::string> args = {"/proc/self/exe", "run", "--dim", "3", "--particles",
                                   std::to_string(n), "--restitution", "0.5", "--t-max", "1",
                                   "--medium", "box", "--snapshot-particles", "active",
                                   "--quiet", "--out", dir.string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  int status = -1;
  rusage ru{};
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) == 0)
    wait4(pid, &status, 0, &ru);
  fs::remove_all(dir);
  const bool ok = pid > 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return ok ? static_cast<double>(ru.ru_maxrss) * 1024.0 : 0.0;
}

// What a resting sphere costs the command, not the engine alone (sim/bytes_per_particle_3d): the
// slope of its peak between N = 2e6 and 4e6 (the same blast in both: the extra spheres rest).
// Measured before the run loop took the active particles alone for its snapshot: 320 and 547 MB,
// 114 B a sphere.
std::vector<Figure> run_peak_per_resting_particle() {
  constexpr std::int64_t kSmall = 2000000, kLarge = 4000000;
  const double small = run_command_peak(kSmall), large = run_command_peak(kLarge);
  const bool ok = small > 0 && large > 0;
  return {{"peak_megabytes_2e6", small / 1e6, "MB", ""},
          {"peak_megabytes_4e6", large / 1e6, "MB", ""},
          {"peak_bytes_per_resting_particle", ok ? (large - small) / (kLarge - kSmall) : 0, "B",
           "<= 40"},
          {"exit_ok", ok ? 1.0 : 0.0, "", "1"}};
}

}  // namespace

void add_run_cases(std::vector<Case>& cases) {
  cases.push_back({"run/peak_bytes_per_particle_3d",
                   "peak resident bytes of the whole `grainshock run` command per resting sphere: "
                   "3D box, r = 0.5, t-max 1, --snapshot-particles active, N = 2e6 and 4e6",
                   false, run_peak_per_resting_particle});
  cases.push_back(
      {"run/kick3d_2e5_vs_2e6",
       "the run loop of `grainshock run`, 3D kick, r = 0.5, to t = 2e4, N = 2e5 and 2e6 "
       "in turns: cost per collision ratio",
       true, run_scaling});
  cases.push_back({"run/checkpoint_2e6",
                   "checkpoint of a 2e6-sphere 3D kick at t = 2e4: write, read", true,
                   checkpoint_2e6});
  cases.push_back({"run/fig1_job",
                   "`grainshock run` with no flags (the Fig. 1 job): pictures-and-movie time, "
                   "wall and CPU time of the whole job",
                   true, fig1_job});
}

}  // namespace gs::bench
