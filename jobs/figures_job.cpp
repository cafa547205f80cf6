#include "jobs/figures_job.h"
#include "jobs/view_job.h"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <utility>

#include "analysis/ensemble_output.h"
#include "analysis/ensemble_runner.h"
#include "analysis/json.h"
#include "analysis/paper.h"
#include "io/atomic_file.h"
#include "io/output_dir.h"
#include "jobs/ensemble_job.h"
#include "jobs/figures_plots.h"
#include "jobs/figures_report.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::jobs {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Wall and CPU seconds; CPU counts every thread of this process and the children it waited for
// (gnuplot), so that a stage's CPU time is what a quiet machine would spend on it.
struct Cost {
  double wall = 0, cpu = 0;
};

double cpu_seconds() {
  double s = 0;
  for (int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
    rusage u{};
    getrusage(who, &u);
    s += double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  }
  return s;
}

class Meter {
 public:
  Cost read() const { return {seconds_since(t0_), cpu_seconds() - c0_}; }

 private:
  Clock::time_point t0_ = Clock::now();
  double c0_ = cpu_seconds();
};

// What one pass over a plan cost, stage by stage, for --estimate.
struct PassCosts {
  std::vector<Cost> runs, fits;  // per case: its realisations; its fits and ensemble folder
  std::vector<double> growth;    // per case: collision_growth of its mean time series
  Cost crossovers;               // phi1 and phi2 readings (resampling realisations)
  Cost figures;                  // Fig. 1's two realisations, the plots, summary and report
};

// d ln C / d ln t of the mean collision count over the last half decade of a run: how a run's
// cost grows at its end, for --estimate to extrapolate a sample shortened in time. In the
// inelastic regime it tends to 1 (the collision rate N_t n v_t ~ t^(alpha d + alpha - 1) = t^0
// with alpha = 1/(d+1)); from the elastic blast before t_c1 it comes down from 1 + d/(d+2), so a
// sample that ends before the rate has settled overestimates.
double collision_growth(const Table& ts) {
  const auto& t = ts.column("t");
  const auto& c = ts.column("collisions");
  const double t_end = t.back();
  std::size_t k = 0;
  while (t[k] < t_end / std::sqrt(10.0)) ++k;
  if (!(c[k] > 0) || !(t_end > t[k])) return std::nan("");
  return std::log(c.back() / c[k]) / std::log(t_end / t[k]);
}

// Where case `c` keeps its finished realisations, and the file there that says which ensemble
// they belong to (its spec, as this build plans it).
fs::path realisations_dir(const fs::path& dir, const FigureCase& c) {
  return dir / "ensembles" / c.name / "realisations";
}
constexpr const char* kCaseSpecFile = "case.toml";

// The first line where two texts differ, in each ("" past its end).
std::pair<std::string, std::string> first_different_lines(const std::string& a,
                                                          const std::string& b) {
  std::istringstream ia(a), ib(b);
  std::string la, lb;
  while (true) {
    const bool more_a = static_cast<bool>(std::getline(ia, la));
    const bool more_b = static_cast<bool>(std::getline(ib, lb));
    if (!more_a) la.clear();
    if (!more_b) lb.clear();
    if (la != lb || (!more_a && !more_b)) return {la, lb};
  }
}

// Makes case `c`'s realisations folder, or checks that the one a stopped job left holds
// realisations of the same ensemble: another version may plan the case otherwise.
fs::path case_realisations(const fs::path& dir, const FigureCase& c) {
  const fs::path rdir = realisations_dir(dir, c);
  const std::string spec = spec_toml(c.spec);
  std::error_code ec;
  if (fs::exists(rdir / kCaseSpecFile, ec)) {
    std::ifstream in(rdir / kCaseSpecFile);
    std::stringstream held;
    held << in.rdbuf();
    if (held.str() != spec) {
      // Most often figures.toml edited since (a seed, a size), else another version's plan.
      const auto [was, now] = first_different_lines(held.str(), spec);
      throw UserError(rdir.string() + ": holds realisations of case " + c.name + " planned with '" +
                      was + "', but the folder's settings (figures.toml) now plan '" + now +
                      "': restore them, or start again with --force");
    }
    return rdir;
  }
  fs::create_directories(rdir, ec);
  if (ec) throw UserError("cannot create '" + rdir.string() + "': " + ec.message());
  write_file_atomic(rdir / kCaseSpecFile, spec);
  return rdir;
}

// The job: every case of the plan, then crossovers, comparisons, figures, summary.json and
// report.md into `dir`; realisations found in `dir` are read instead of run (resume). The
// estimate runs the same pass on a sampled plan.
FiguresResult run_pass(const FiguresOptions& o, const FiguresPlan& plan, const fs::path& dir,
                       PassCosts* costs) {
  const auto t0 = Clock::now();
  std::vector<CaseResult> results;
  std::uint64_t total = 0, done_before = 0, resumed = 0;
  for (const auto& c : plan.cases) total += c.spec.realisations;
  const auto progress = open_progress(o.progress);
  std::vector<Comparison> cmp;
  for (const auto& c : plan.cases) {
    RunnerOptions ro;
    ro.threads = c.threads_of(o.threads);
    ro.realisations_dir = case_realisations(dir, c);
    ro.checkpoint_interval = 60 * o.checkpoint_minutes;
    ro.on_warning = [&o](const std::string& what) { tell(o.messages, MessageKind::Warning, what); };
    const std::uint64_t held = finished_realisations(ro.realisations_dir, c.spec).size();
    ro.on_progress = [&](std::uint64_t done, std::uint64_t) {
      progress->update(double(done_before + held + done) / double(total),
                       c.name + ": " + std::to_string(held + done) + " of " +
                           std::to_string(c.spec.realisations) + " realisations");
    };
    if (held > 0) ro.on_progress(0, 0);  // resumed: the line shows what was read back
    const Meter run_meter;
    RunnerResult r = run_ensemble(c.spec, ro);
    if (r.interrupted) {
      progress->done();
      return {dir, seconds_since(t0), {}, true};
    }
    const Cost run_cost = run_meter.read();
    const std::uint64_t run_now = r.sums.count() - r.resumed;
    resumed += r.resumed;
    const Meter fit_meter;
    done_before += c.spec.realisations;
    const auto edir = dir / "ensembles" / c.name;
    CaseResult cr{&c, std::move(r.sums), {}, run_cost.wall};
    cr.fits = write_ensemble_folder(edir, cr.sums, FitOptions{}, cr.wall, o.threads, run_now);
    if (!c.delta_scan) {
      const CaseContext context{c.name, slope_figure_of(c), c.collapse, c.superseded_for_alpha,
                                c.role == CaseRole::Packing};
      auto more = case_comparisons(context, c.spec, cr.fits);
      // The snowplow runs answer their own question (the report's section), not the paper's.
      if (c.role == CaseRole::Snowplow)
        for (auto& m : more)
          if (m.role == Role::Counted) m.role = Role::Reported;
      cmp.insert(cmp.end(), more.begin(), more.end());
    }
    results.push_back(std::move(cr));
    if (costs) {
      costs->runs.push_back(run_cost);
      costs->fits.push_back(fit_meter.read());
      costs->growth.push_back(collision_growth(results.back().sums.timeseries()));
    }
  }
  progress->done();
  const double sim_wall = seconds_since(t0);

  const Meter crossover_meter;
  const Crossovers x = crossovers_of(results);
  if (costs) costs->crossovers = crossover_meter.read();
  const Meter figure_meter;
  for (const auto& set : x.tc1) cmp.push_back(phi1_comparison(set.d, set.fit, false));
  for (const auto& set : x.tc1_theory_b) cmp.push_back(phi1_comparison(set.d, set.fit, true));
  for (const auto& set : x.tc1) cmp.push_back(phi1_elastic_limit_comparison(set.d, set.local));
  for (const auto& set : x.tc1) {
    cmp.push_back(phi1_energy_comparison(set.d, set.energy, std::nan("")));
    for (double level : Phi1Options{}.levels)
      cmp.push_back(phi1_energy_comparison(set.d, set.energy, level));
  }
  for (const auto& set : x.fractions)  // E_0/2's points: the short runs near r = 1 (--limit)
    if (set.rule == "time to E_0 x " + figure_number(0.5, 3))
      cmp.push_back(phi1_near_elastic_comparison(set.d, set.points));
  cmp.push_back(phi2_comparison(x.tc2.front().d, 0.1, x.tc2.front().fit));
  const std::vector<std::string> problems = write_figures(plan, results, x, dir, o.formats);
  const FiguresRun run{o.mode, o.seed, o.threads, seconds_since(t0), sim_wall, resumed, plan.fig1};
  write_figures_summary(dir, run, results, cmp, problems);
  write_figures_report(dir, run, results, x, cmp, problems);
  if (o.page) write_folder_page(dir.string(), "report.html", o.messages);
  if (costs) costs->figures = figure_meter.read();
  return {dir, run.wall, problems};
}

// --estimate: the whole job with `sample` realisations per case, in a scratch folder removed
// after, each stage timed: a case's realisations scaled by M / sample (run `threads` at a time:
// ceil(M / threads) rounds), the rest as measured. A case with an estimate_t_max (--limit's,
// hours long) samples only to that time, its cost per realisation scaled by (t_max /
// estimate_t_max)^g, g the collisions' growth at the sample's end (collision_growth). The fits and
// the phi1/phi2 readings cost about the same for 2 realisations as for 16: their resampling works
// on the time grid (200 draws of a plateau search), and summing a draw's realisations is cheap.
// Measured (CPU-s, 2 threads, sample 2): --tiny 17.2 estimated, 16.9 run; --quick 250 estimated,
// 242 run; scaling the fits by M / sample too gave 22.5 and 324. From CPU time, which another
// program on the machine changes least, that is the wall time on a quiet machine with `threads`
// cores; from wall time, on this machine as loaded now.
// False if stopped (SIGINT/SIGTERM) before the sample finished.
bool estimate(const FiguresOptions& o, const FiguresPlan& plan, const fs::path& dir) {
  FiguresPlan sampled = plan;
  for (auto& c : sampled.cases) {
    c.spec.realisations = std::min<std::uint64_t>(c.spec.realisations, std::uint64_t(o.sample));
    if (c.estimate_t_max > 0) {
      const double f = c.estimate_t_max / c.spec.physics.t_max;
      c.spec.physics.t_max = c.estimate_t_max;
      for (double& t : c.spec.snapshot_times) t *= f;
    }
  }
  const fs::path scratch = dir / "estimate_sample";
  fs::create_directories(scratch);
  PassCosts costs;
  FiguresOptions so = o;
  so.progress = {};
  const bool stopped = run_pass(so, sampled, scratch, &costs).interrupted;
  fs::remove_all(scratch);
  if (stopped) return false;

  Json j;
  j["mode"] = to_string(plan.mode);
  j["threads"] = o.threads;
  j["sample_per_case"] = o.sample;
  Json& cases = j["cases"] = Json::array();
  std::ostringstream table;
  table << "| stage | N | t_max | M | sample wall (s) | sample CPU (s) | CPU s per realisation | "
           "estimated CPU (s) | estimated wall, quiet (s) | estimated wall, this load (s) |\n"
           "|---|---|---|---|---|---|---|---|---|---|\n";
  double total = 0, total_cpu = 0, total_quiet = 0;
  auto row = [&](const std::string& stage, const std::string& n, const std::string& t_max,
                 const std::string& m, const Cost& sample, const std::string& per, double cpu,
                 double quiet, double wall) {
    table << "| " << stage << " | " << n << " | " << t_max << " | " << m << " | "
          << figure_number(sample.wall) << " | " << figure_number(sample.cpu) << " | " << per
          << " | " << figure_number(cpu) << " | " << figure_number(quiet) << " | "
          << figure_number(wall) << " |\n";
    total += wall;
    total_cpu += cpu;
    total_quiet += quiet;
  };
  for (std::size_t k = 0; k < plan.cases.size(); ++k) {
    const FigureCase& c = plan.cases[k];
    const double threads = c.threads_of(o.threads);
    const double m = double(c.spec.realisations), s = double(sampled.cases[k].spec.realisations);
    const Cost run = costs.runs[k], fit = costs.fits[k];
    const double sample_t = sampled.cases[k].spec.physics.t_max;
    const double longer = std::pow(c.spec.physics.t_max / sample_t, costs.growth[k]);
    const double per = run.cpu / s * longer;
    // Realisations run `threads` at a time: the last round may leave threads idle.
    const double rounds = std::ceil(m / threads);
    const double quiet_run = per * rounds;
    const double wall_run = run.wall / std::ceil(s / threads) * rounds * longer;
    cases.push_back({{"case", c.name},
                     {"particles", c.spec.physics.particles},
                     {"t_max", c.spec.physics.t_max},
                     {"realisations", c.spec.realisations},
                     {"threads", threads},
                     {"sample_t_max", sample_t},
                     {"collision_growth", costs.growth[k]},
                     {"sample_wall_seconds", run.wall},
                     {"cpu_seconds_per_realisation", per},
                     {"fit_cpu_seconds_of_sample", fit.cpu},
                     {"estimated_cpu_seconds", per * m + fit.cpu},
                     {"estimated_wall_seconds", wall_run + fit.wall},
                     {"estimated_wall_seconds_from_cpu", quiet_run + fit.cpu}});
    const std::string stage =
        c.name + " (runs + fits" +
        (c.estimate_t_max > 0 ? "; sample to t = " + figure_number(sample_t, 3) +
                                    ", cost x (t_max / t)^" + figure_number(costs.growth[k], 3)
                              : std::string()) +
        ")";
    row(stage, std::to_string(c.spec.physics.particles), figure_number(c.spec.physics.t_max),
        std::to_string(c.spec.realisations), {run.wall + fit.wall, run.cpu + fit.cpu},
        figure_number(per), per * m + fit.cpu, quiet_run + fit.cpu, wall_run + fit.wall);
  }
  row("phi1 and phi2 readings", "", "", "", costs.crossovers, "", costs.crossovers.cpu,
      costs.crossovers.cpu, costs.crossovers.wall);
  row("Fig. 1 (one realisation each, " + std::to_string(plan.fig1.a.particles) +
          " discs), plots, report",
      "", "", "", costs.figures, "", costs.figures.cpu, costs.figures.cpu, costs.figures.wall);
  // Serial stages, as measured.
  j["readings_cpu_seconds"] = costs.crossovers.cpu;
  j["figures_cpu_seconds"] = costs.figures.cpu;
  j["estimated_cpu_seconds"] = total_cpu;
  j["estimated_wall_seconds_from_cpu"] = total_quiet;
  j["estimated_wall_seconds"] = total;
  write_file_atomic(dir / "estimate.json", json_text(j));
  std::ostringstream md;
  md << "# Time estimate of `grainshock figures --" << to_string(plan.mode)
     << (o.long_3d ? " --long" : "") << (o.limit ? " --limit" : "")
     << (o.limit && o.limit_dim != 0 ? " --limit-dim " + std::to_string(o.limit_dim) : "")
     << (o.snowplow ? " --snowplow" : "") << "`\n\n"
     << "The whole job run with " << o.sample << " realisations per case on " << o.threads
     << " threads, each stage timed: a case's realisations scaled to the plan by M / " << o.sample
     << " in rounds of " << o.threads
     << " (ceil(M / threads) rounds; one at a time where a case's memory needs it); its fits, the "
        "phi1 and phi2 readings, Fig. 1 and the "
        "plots as measured (the fits and readings resample on the time grid and cost about the "
        "same for 2 realisations as for 16: --quick estimated 250 CPU-s, ran 242). A stage "
        "sampled to a shorter t has its cost per realisation scaled by (t_max / t)^g, g = d ln "
        "(collisions) / d ln t over the sample's last half decade (1 in the inelastic regime, "
        "more before it, so an overestimate if the sample ends before the rate settles; the cost "
        "per collision of a larger medium is taken as the sample's). CPU time "
        "counts every thread and gnuplot. "
        "'Quiet': the wall time on an otherwise idle machine with "
     << o.threads << " cores, from CPU time; 'this load': from the wall time measured now.\n\n"
     << table.str() << "\n**Total: " << figure_number(total_cpu) << " CPU-s; wall on a quiet "
     << o.threads << "-core machine " << figure_number(total_quiet) << " s ("
     << figure_number(total_quiet / 60, 3) << " min); at this load " << figure_number(total)
     << " s (" << figure_number(total / 60, 3) << " min).**\n";
  write_file_atomic(dir / "estimate.md", md.str());
  if (!o.quiet) {
    char line[200];
    std::snprintf(line, sizeof line,
                  "estimated %.4g CPU-s: %.4g s (%.3g min) wall on a quiet %d-core machine, %.4g s "
                  "at this load",
                  total_cpu, total_quiet, total_quiet / 60, o.threads, total);
    tell(o.messages, MessageKind::Note, line);
  }
  return true;
}

// What a figures job writes that a new job in the same folder (--force) must not find; an
// estimate replaces only its scratch, leaving a job's results beside it.
constexpr const char* kReplaced[] = {"ensembles", "estimate_sample", "figures.toml", "report.md",
                                     "summary.json"};
constexpr const char* kEstimateReplaced[] = {"estimate_sample"};

}  // namespace

FiguresResult run_figures_job(const FiguresOptions& o) {
  check_threads(o.threads);
  if (o.sample < 1) throw UsageError("--sample must be at least 1");
  checked_checkpoint_minutes(o.checkpoint_minutes);
  if (o.limit_dim != 0 && o.limit_dim != 2 && o.limit_dim != 3)
    throw UsageError("--limit-dim must be 2 or 3");
  if (o.limit_dim != 0 && !o.limit) throw UsageError("--limit-dim needs --limit");
  if (o.resume && o.estimate) throw UsageError("an estimate cannot be resumed");
  const FiguresPlan plan =
      figures_plan(o.mode, o.seed, o.long_3d, o.limit, o.limit_dim, o.snowplow);
  FiguresResult out;
  if (o.resume) {
    out.dir = o.out;
    if (!is_unfinished_figures_folder(out.dir))
      throw UserError("'" + o.out + "' holds no unfinished figures job (figures.toml without " +
                      "report.md): nothing to resume");
    lock_output_dir(out.dir);
    remove_leftovers(out.dir);
  } else {
    if (!o.force && is_unfinished_figures_folder(o.out))
      throw UserError("--out " + o.out + ": holds an unfinished figures job; continue it with: " +
                      "grainshock resume " + o.out + ", or use --force to start again");
    out.dir = o.estimate ? prepare_output_dir(o.out, o.force, kEstimateReplaced)
                         : prepare_output_dir(o.out, o.force, kReplaced);
    lock_output_dir(out.dir);  // a resume of it meanwhile would run the same realisations
  }
  const fs::path& dir = out.dir;
  install_stop_handlers();
  const auto t0 = Clock::now();
  if (o.estimate) {
    out.interrupted = !estimate(o, plan, dir);
    out.wall = seconds_since(t0);
    return out;
  }
  if (!o.resume && !o.settings.empty()) write_file_atomic(dir / "figures.toml", o.settings);
  // The realisations stay (a few MB): hours of --snowplow or --limit runs can be fitted again by
  // a newer build, report.md removed and `grainshock resume DIR` reading them back.
  return run_pass(o, plan, dir, nullptr);
}

bool is_unfinished_figures_folder(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "figures.toml", ec) && !fs::exists(dir / "report.md", ec);
}

}  // namespace gs::jobs
